// The page's service worker: after the first load the page opens, and practice goes on, with the
// network off. scripts/build-web writes the build's version and its file list below, so each
// build has its own cache, filled whole when the worker installs: the page, its engine and
// KaTeX always come from one build, never a mix. Only GET requests to this page's own origin
// are answered; everything else goes to the network untouched.
const VERSION = '__LAGRANGE_BUILD__';
const FILES = ['__LAGRANGE_FILES__'];
const CACHE = `lagrange-page-${VERSION}`;
// Problem files a page URL names (`?problems=sets/a.toml`): fetched fresh when the network is
// there, and the last copy served when it is not.
const FILES_CACHE = 'lagrange-problem-files';
const BASE = new URL('./', self.location.href);

self.addEventListener('install', (event) => {
  event.waitUntil((async () => {
    const cache = await caches.open(CACHE);
    // `reload`: the files themselves, never an older copy from the HTTP cache.
    await cache.addAll(FILES.map((f) => new Request(new URL(f, BASE), { cache: 'reload' })));
    await self.skipWaiting();
  })());
});

self.addEventListener('activate', (event) => {
  event.waitUntil((async () => {
    for (const name of await caches.keys()) {
      if (name.startsWith('lagrange-page-') && name !== CACHE) await caches.delete(name);
    }
    await self.clients.claim();
  })());
});

/** The precached file a same-origin URL names, or null: the page itself for any query. */
function precached(url, request) {
  if (!url.href.startsWith(BASE.href)) return null;
  const path = url.pathname.slice(BASE.pathname.length);
  if (request.mode === 'navigate' && (path === '' || path === 'index.html')) return 'index.html';
  return FILES.includes(path) ? path : null;
}

async function fromCache(file, request) {
  const hit = await caches.match(new URL(file, BASE).href, { cacheName: CACHE });
  return hit ?? fetch(request);
}

/** The network first (a teacher may have changed the file), the last good copy offline. */
async function networkFirst(request) {
  const cache = await caches.open(FILES_CACHE);
  try {
    const response = await fetch(request);
    if (response.ok) await cache.put(request, response.clone());
    return response;
  } catch (e) {
    const hit = await cache.match(request);
    if (hit) return hit;
    throw e;
  }
}

self.addEventListener('fetch', (event) => {
  const request = event.request;
  if (request.method !== 'GET') return;
  const url = new URL(request.url);
  if (url.origin !== self.location.origin) return;
  const file = precached(url, request);
  if (file) {
    event.respondWith(fromCache(file, request));
  } else if (request.mode !== 'navigate' && url.pathname.endsWith('.toml')) {
    event.respondWith(networkFirst(request));
  }
});
