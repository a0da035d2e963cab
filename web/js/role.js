// The role of the viewer's token (GET /api/access, docs/API.md "Security"): a viewer's token may not
// start fits at a new ε nor store to a PACS, so those controls are greyed out for it.
import { withToken } from './access.js';

// Said by a control greyed out for a viewer's token.
export const OPERATOR_REASON = "Needs an operator's token";

let role = 'operator'; // until the server has said otherwise

// Whether the token is a viewer's: the code that enables a control again keeps it greyed then.
export function isViewerRole() {
  return role === 'viewer';
}

// Marks the page with data-role and disables `controls` for a viewer; returns the role.
export async function applyRole(controls) {
  try {
    const res = await fetch('api/access', withToken());
    if (res.ok) role = (await res.json()).role;
  } catch {
    // No answer: the requests themselves will say what is wrong.
  }
  document.body.dataset.role = role;
  if (isViewerRole()) {
    for (const control of controls) {
      control.disabled = true;
      control.title = OPERATOR_REASON;
    }
  }
  return role;
}
