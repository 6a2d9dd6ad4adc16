// Recordings from the page (`throng serve --recordings DIR`, docs/viewer.md): the row under the
// camera buttons lists DIR's recordings (GET /api/recordings: name, scenario, duration, agents,
// size), Open asks the server to play the one picked (POST /api/recordings/open) — the server then
// switches every viewer to it: each is told and reconnects, and LiveSource, finding another world
// in the new Welcome, reloads the page — and Upload sends a .sqlite file (POST
// /api/recordings?name=FILE, the file as the body), which the server stores under a safe unique
// name once it checks as a throng recording, else answers one message naming what was wrong. While
// a recording plays on a server started with a scenario, Live (POST /api/recordings/live) takes
// every viewer back to that live scenario, the same way (it starts afresh). The
// row stays hidden when the server has no --recordings directory ("dir": null) or there is no server.
// describeRecording and formatBytes are pure (test/recordings.test.js).

/** "1.5 MB", "230 kB", "512 B" (decimal units, as file managers show sizes). */
export function formatBytes(n) {
  const b = Number(n) || 0;
  if (b >= 1e9) return `${(b / 1e9).toFixed(1)} GB`;
  if (b >= 1e6) return `${(b / 1e6).toFixed(1)} MB`;
  if (b >= 1e3) return `${Math.round(b / 1e3)} kB`;
  return `${b} B`;
}

function clock(seconds) {
  const s = Math.max(0, Math.round(Number(seconds) || 0));
  return `${Math.floor(s / 60)}:${String(s % 60).padStart(2, '0')}`;
}

/** One line of the list: "museum.sqlite — museum, 0:20, 14 agents, 230 kB" (or why it is unreadable). */
export function describeRecording(r) {
  if (r.error) return `${r.name} — unreadable: ${r.error}`;
  const agents = `${r.agents} agent${r.agents === 1 ? '' : 's'}`;
  return `${r.name} — ${r.scenario || '?'}, ${clock(r.duration)}, ${agents}, ${formatBytes(r.size)}`;
}

export class RecordingsPanel {
  /** `els`: {row, list, open, upload, status, live} elements; `fetchImpl` for tests. */
  constructor(els, fetchImpl = globalThis.fetch.bind(globalThis)) {
    this.els = els;
    this.fetch = fetchImpl;
    this.recordings = [];
    this.playing = null;
    this.maxUploadBytes = 0;
    this.live = null;  // the live scenario's file name, null when the server started with a recording
    els.open.addEventListener('click', () => this.open(els.list.value));
    if (els.live) els.live.addEventListener('click', () => this.goLive());
    els.upload.addEventListener('change', () => {
      const file = els.upload.files && els.upload.files[0];
      if (file) this.upload(file).finally(() => { els.upload.value = ''; });
    });
  }

  say(text, error = false) {
    this.els.status.textContent = text;
    this.els.status.classList.toggle('error', error);
  }

  /** Fetches the list; shows the row when the server has a recordings directory. `select`: the name to pick. */
  async refresh(select = null) {
    let answer;
    try {
      answer = await this.fetch('api/recordings');
    } catch {
      return false;
    }
    if (!answer.ok) return false;
    const body = await answer.json();
    if (!body.dir) return false;  // no --recordings directory
    this.recordings = body.recordings || [];
    this.playing = body.playing || null;
    this.maxUploadBytes = body.maxUploadBytes || 0;
    this.live = body.live || null;
    const { list, row, open, live } = this.els;
    if (live) {
      // Shown while a recording plays and there is a live scenario to go back to.
      live.classList.toggle('hidden', !(this.live && this.playing));
      live.title = this.live ? `back to the live scenario ${this.live} (for every viewer of this server; it starts afresh)` : '';
    }
    list.replaceChildren(...this.recordings.map((r) => {
      const o = document.createElement('option');
      o.value = r.name;
      o.textContent = `${r.name === this.playing ? '▶ ' : ''}${describeRecording(r)}`;
      o.disabled = !!r.error;
      return o;
    }));
    const pick = select || this.playing;
    if (pick && this.recordings.some((r) => r.name === pick)) list.value = pick;
    open.disabled = this.recordings.length === 0;
    list.title = `recordings in ${body.dir} (throng serve --recordings)`;
    row.classList.remove('hidden');
    return true;
  }

  /** Asks the server to play `name` for every viewer; the page reloads when the new world arrives. */
  async open(name) {
    if (!name) return;
    this.say(`opening ${name}…`);
    const answer = await this.fetch('api/recordings/open', {
      method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ name }),
    });
    const body = await answer.json().catch(() => ({}));
    if (!answer.ok) { this.say(body.error || `could not open ${name} (HTTP ${answer.status})`, true); return; }
    this.say(`${name} opened: loading it…`);
  }

  /** Asks the server to play its live scenario again, for every viewer; the page reloads into it. */
  async goLive() {
    this.say(`back to ${this.live || 'the live scenario'}…`);
    let answer;
    try {
      answer = await this.fetch('api/recordings/live', { method: 'POST' });
    } catch (e) {
      this.say(`could not go back to the live scenario (${e.message})`, true);
      return;
    }
    const body = await answer.json().catch(() => ({}));
    if (!answer.ok) { this.say(body.error || `could not go back to the live scenario (HTTP ${answer.status})`, true); return; }
    this.say(`${this.live || 'the live scenario'}: loading it…`);
  }

  /** Uploads `file` (a File or Blob with a name); refreshes the list and picks the stored name. */
  async upload(file) {
    if (this.maxUploadBytes && file.size > this.maxUploadBytes) {
      this.say(`${file.name}: too large (${formatBytes(file.size)}); the server takes at most ${formatBytes(this.maxUploadBytes)}`, true);
      return null;
    }
    this.say(`uploading ${file.name} (${formatBytes(file.size)})…`);
    let answer;
    try {
      answer = await this.fetch(`api/recordings?name=${encodeURIComponent(file.name)}`, {
        method: 'POST', headers: { 'Content-Type': 'application/octet-stream' }, body: file,
      });
    } catch (e) {
      this.say(`${file.name}: upload failed (${e.message})`, true);
      return null;
    }
    const body = await answer.json().catch(() => ({}));
    if (!answer.ok) {
      this.say(body.error || `${file.name}: upload refused (HTTP ${answer.status})`, true);
      return null;
    }
    await this.refresh(body.name);
    this.say(`stored as ${body.name}: Open plays it`);
    return body;
  }
}
