// The role of the viewer's token (GET /api/access, docs/API.md "Security"): a viewer's token may not
// start fits at a new ε nor store to a PACS, so those controls are greyed out for it.
import { withToken } from './access.js';

// Marks the page with data-role and disables `controls` for a viewer; returns the role.
export async function applyRole(controls) {
  let role = 'operator';
  try {
    const res = await fetch('api/access', withToken());
    if (res.ok) role = (await res.json()).role;
  } catch {
    // No answer: the requests themselves will say what is wrong.
  }
  document.body.dataset.role = role;
  if (role === 'viewer') {
    for (const control of controls) {
      control.disabled = true;
      control.title = "Needs an operator's token";
    }
  }
  return role;
}
