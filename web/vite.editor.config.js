// Vite build of the scenario editor: web/editor/index.html → web/dist/editor/ (what `throng edit`
// serves), after the viewer's build (vite.config.js) has emptied web/dist. The editor imports the
// scenario JSON Schema from scenarios/schema at build time (its model forms). The dev server
// proxies /api to a local `throng edit` on :8080 (override with THRONG_SERVER=host:port).
import { defineConfig } from 'vite';

const server = process.env.THRONG_SERVER || '127.0.0.1:8080';

export default defineConfig({
  root: 'editor',
  base: './',
  build: {
    outDir: '../dist/editor',
    emptyOutDir: false,
    target: ['es2022', 'chrome107', 'edge107', 'firefox104', 'safari16'],
  },
  server: {
    fs: { allow: ['..', '../../scenarios/schema'] },
    proxy: { '/api': { target: `http://${server}` } },
  },
});
