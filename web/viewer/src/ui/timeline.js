// Replay timeline: play/pause, scrub, speed; shows time / duration. Drives a source with play(),
// pause(), seek(t) and setSpeed(s) and follows its 'timeline' events ({time, duration, playing,
// speed}).
function fmt(t) {
  const m = Math.floor(t / 60), s = Math.floor(t % 60);
  return `${m}:${String(s).padStart(2, '0')}`;
}

export class Timeline {
  constructor(root, source) {
    this.root = root;
    this.source = source;
    this.play = root.querySelector('#tl-play');
    this.scrub = root.querySelector('#tl-scrub');
    this.label = root.querySelector('#tl-time');
    this.speed = root.querySelector('#tl-speed');
    this.dragging = false;
    root.classList.remove('hidden');
    this.play.onclick = () => (this.state && this.state.playing ? source.pause() : source.play());
    this.scrub.addEventListener('input', () => {
      this.dragging = true;
      source.seek((this.scrub.value / 1000) * (this.state ? this.state.duration : 0));
    });
    this.scrub.addEventListener('change', () => { this.dragging = false; });
    this.speed.onchange = () => source.setSpeed(Number(this.speed.value));
    source.on('timeline', (s) => this.update(s));
  }

  update(s) {
    this.state = s;
    this.play.textContent = s.playing ? '❚❚' : '▶';
    if (!this.dragging && s.duration > 0) this.scrub.value = String(Math.round((s.time / s.duration) * 1000));
    this.label.textContent = `${fmt(s.time)} / ${fmt(s.duration)}`;
  }
}
