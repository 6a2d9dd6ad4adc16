// Minimal event emitter for data sources: on(event, fn) → unsubscribe, emit(event, value).
export class Emitter {
  constructor() { this.handlers = new Map(); }
  on(event, fn) {
    if (!this.handlers.has(event)) this.handlers.set(event, new Set());
    this.handlers.get(event).add(fn);
    return () => this.handlers.get(event).delete(fn);
  }
  emit(event, value) {
    const hs = this.handlers.get(event);
    if (hs) for (const fn of hs) fn(value);
  }
}
