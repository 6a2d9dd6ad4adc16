// Vite build of the browser viewer: web/viewer/index.html → web/dist/ (what `throng serve` serves).
// Relative asset paths so the page works from any mount point; the dev server proxies /ws and
// /motions to a local `throng serve` on :8080 (override with THRONG_SERVER=host:port).
// Vite 6 (not 7 or 8) because it runs on Debian 12's own node 18 (docs/viewer.md); the browsers
// targeted are those of Vite 7's default ("baseline widely available"), not Vite 6's older ones.
import { defineConfig } from 'vite';

const server = process.env.THRONG_SERVER || '127.0.0.1:8080';

export default defineConfig({
  root: 'viewer',
  base: './',
  build: {
    outDir: '../dist',
    emptyOutDir: true,
    chunkSizeWarningLimit: 1200,
    target: ['es2022', 'chrome107', 'edge107', 'firefox104', 'safari16'],
  },
  server: {
    proxy: {
      '/ws': { target: `ws://${server}`, ws: true },
      '/motions': { target: `http://${server}` },
    },
  },
});
