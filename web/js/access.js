// The access token of a server exposed beyond loopback (docs/API.md, "Security"): read from the URL hash
// (#...&token=T), sent as the Authorization header on fetches and as token= where no header can go.

let token = '';

// Takes token= from a URL hash; a hash without one (a pasted link) keeps the token already known.
export function adoptToken(hash) {
  const found = new URLSearchParams(hash.replace(/^#/, '')).get('token');
  if (found) token = found;
  return token;
}

// Appended to the view's hash, so a reload or a copied link still carries the token.
export function tokenHashPart() {
  return token ? `&token=${encodeURIComponent(token)}` : '';
}

// fetch() options with the token's Authorization header added.
export function withToken(init = {}) {
  if (!token) return init;
  return { ...init, headers: { ...(init.headers || {}), Authorization: `Bearer ${token}` } };
}

// The URL with token= added, for EventSource, which cannot send headers.
export function withTokenQuery(url) {
  if (!token) return url;
  return `${url}${url.includes('?') ? '&' : '?'}token=${encodeURIComponent(token)}`;
}
