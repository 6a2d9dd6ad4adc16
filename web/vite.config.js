// Vite build of the browser viewer: web/viewer/index.html → web/dist/ (what `throng serve` serves).
// Relative asset paths so the page works from any mount point; the dev server proxies /ws and
// /motions to a local `throng serve` on :8080 (override with THRONG_SERVER=host:port).
import { defineConfig } from 'vite';

const server = process.env.THRONG_SERVER || '127.0.0.1:8080';

export default defineConfig({
  root: 'viewer',
  base: './',
  build: { outDir: '../dist', emptyOutDir: true, chunkSizeWarningLimit: 1200 },
  server: {
    proxy: {
      '/ws': { target: `ws://${server}`, ws: true },
      '/motions': { target: `http://${server}` },
    },
  },
});
