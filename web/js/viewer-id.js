// This page's one random id: the server lets a page's newer render or fit supersede its older one.
export const VIEWER_ID = [...crypto.getRandomValues(new Uint8Array(8))]
  .map((b) => b.toString(16).padStart(2, '0'))
  .join('');
