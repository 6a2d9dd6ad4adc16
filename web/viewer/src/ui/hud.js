// Heads-up display: agents, participants, frames per second, kbit/s received, levels of detail
// in use (and the LOD budget's caps). Also publishes the same numbers as window.__throngStats for
// scripts (bench/fps.mjs).
export class Hud {
  constructor(el) {
    this.el = el;
    this.frames = 0;
    this.windowStart = performance.now();
    this.fps = 0;
    this.kbps = 0;
    this.lastBytes = 0;
    this.totalFrames = 0;
  }

  /** Once per rendered frame. */
  tick(source, counts, agents, lod) {
    this.frames++;
    this.totalFrames++;
    const now = performance.now();
    const dt = now - this.windowStart;
    if (dt >= 1000) {
      this.fps = (this.frames * 1000) / dt;
      this.kbps = ((source.bytesReceived - this.lastBytes) * 8) / dt;  // bits per ms = kbit/s
      this.lastBytes = source.bytesReceived;
      this.frames = 0;
      this.windowStart = now;
      this.draw(source, counts, agents, lod);
    }
    globalThis.__throngStats = {
      fps: this.fps, agents, frames: this.totalFrames, kbps: this.kbps,
      lod: { near: counts.near, middle: counts.middle, far: counts.far, dot: counts.dot || 0, hidden: counts.hidden,
        renderScale: lod.adaptive ? lod.renderScale : 1 },
      adaptive: lod.adaptive, participants: source.participants,
    };
  }

  draw(source, counts, agents, lod) {
    const cap = lod.adaptive ? `caps ${lod.maxNear}/${lod.maxMiddle} res ${Math.round(lod.renderScale * 100)}%` : 'LOD off';
    this.el.textContent = [
      `agents       ${agents}`,
      `participants ${source.participants}`,
      `fps          ${this.fps.toFixed(1)}`,
      `kbit/s       ${this.kbps.toFixed(1)}`,
      `near         ${counts.near}`,
      `middle       ${counts.middle}`,
      `far          ${counts.far}`,
      `dots         ${counts.dot || 0}`,
      `off screen   ${counts.hidden}`,
      `${cap}`,
      source.rttMs ? `rtt          ${source.rttMs.toFixed(0)} ms` : `source       ${source.kind}`,
    ].join('\n');
  }
}
