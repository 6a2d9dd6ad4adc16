// The help overlay (key ? or H, the ? button; Esc closes): every key of ui/keys.js's table and the
// mouse, in two short tables. Writes the #help panel.
import { kKeys, kMouse } from './keys.js';

export class Help {
  constructor(root) {
    this.root = root;
    const rows = (list) => list.map((k) => `<tr><th>${k.keys}</th><td>${k.what}</td></tr>`).join('');
    root.innerHTML = `<div class="title">Keys <button class="x" title="close (Esc)">×</button></div>
      <table>${rows(kKeys)}</table><div class="title">Mouse</div><table>${rows(kMouse)}</table>`;
    root.querySelector('.x').onclick = () => this.show(false);
  }

  get shown() { return !this.root.classList.contains('hidden'); }

  show(on = !this.shown) { this.root.classList.toggle('hidden', !on); }
}
