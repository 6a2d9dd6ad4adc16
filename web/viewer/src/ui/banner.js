// Connection banner: hidden while connected; red "connection lost — reconnecting in N s" while
// the live source retries; red "closed" when it gives up (refused); blue for information.
export class Banner {
  constructor(el) { this.el = el; this.timer = null; }
  show(status) {
    clearInterval(this.timer);
    const el = this.el;
    if (status.state === 'open') { el.classList.add('hidden'); return; }
    el.classList.remove('hidden');
    el.classList.toggle('info', status.state === 'connecting');
    if (status.state === 'lost') {
      const until = performance.now() + status.retryIn * 1000;
      const draw = () => {
        const s = Math.max(0, (until - performance.now()) / 1000);
        el.textContent = `Connection lost (${status.text}) — reconnecting in ${s.toFixed(1)} s`;
      };
      draw();
      this.timer = setInterval(draw, 100);
    } else if (status.state === 'closed') {
      el.textContent = `Disconnected: ${status.text}`;
    } else {
      el.textContent = status.text;
    }
  }
}
