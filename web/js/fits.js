// Fits: which eps each dataset has fitted, starting or joining the fit for an eps, and its progress bar.
import { followJob, startFit } from './api.js';
import { VIEWER_ID } from './viewer-id.js';

// progress: {box, bar, label} elements. banner: createBanner's object. showFacts({votCount, fitSeconds})
// shows a finished fit's numbers; onStart(eps) runs when a fit starts being waited for; onReady(eps, {refitted})
// runs once frames may use eps (refitted: through a fit job, a Vot-Space the page has not drawn yet); onChange()
// whenever the status may differ.
export function createFits({ progress, banner, showFacts, onStart, onReady, onChange }) {
  const fitted = new Map(); // "dataset/frame" -> Set of eps known to be fitted
  let token = 0; // bumped per request, so the answers of a superseded one are dropped
  let follow = null;
  let fitting = null; // {eps, progress, stage}

  function markFitted(name, eps) {
    if (!fitted.has(name)) fitted.set(name, new Set());
    fitted.get(name).add(eps);
  }

  // A .vots dataset's one eps is its file. A volume's default eps is asked for like any other: the server
  // answers at once when it has prepared it, and otherwise the page shows the fit's progress (and the
  // exact grid meanwhile) instead of a /render that waits silently for the whole fit.
  function isFitted(name, eps, fixedEps) {
    if (fixedEps) return true;
    return fitted.has(name) && fitted.get(name).has(eps);
  }

  function setProgress(p, stage) {
    const value = Math.min(1, Math.max(0, Number(p) || 0));
    fitting.progress = value;
    fitting.stage = stage || fitting.stage;
    progress.bar.value = value;
    progress.label.textContent = `${Math.round(value * 100)} %${fitting.stage ? ` ${fitting.stage}` : ''}`;
    onChange();
  }

  // Starts (or joins) the fit for eps; frames keep the old eps until it is done, then swap.
  // eps: null or 0 when the server sent no default and the user chose none. fixedEps: the dataset is
  // drawn at eps alone (a .vots file), there is nothing to fit.
  // frame: the 3D volume of a 4D dataset (each is fitted on its own).
  async function ensure({ dataset, frame = 0, eps, degree, fixedEps = false }) {
    const fitName = `${dataset}/${frame}`;
    if (follow) follow.cancel();
    follow = null;
    if (!(eps > 0)) {
      // Only the server knows the default rule: with no default and no choice there is nothing to fit.
      token++;
      fitting = null;
      progress.box.hidden = true;
      banner.show(`No error bound ε for '${dataset}': the server sent no default; choose one with the ε slider.`, 'fit');
      return;
    }
    if (isFitted(fitName, eps, fixedEps)) {
      // Supersede a fit still in flight for another eps: its reply must not swap frames away from this one.
      token++;
      fitting = null;
      progress.box.hidden = true;
      onReady(eps);
      return;
    }
    const mine = ++token;
    fitting = { eps, progress: 0, stage: 'queued' };
    progress.box.hidden = false;
    setProgress(0, 'queued');
    try {
      const job = await startFit({ dataset, frame, eps, degree, client: VIEWER_ID });
      if (mine !== token) return;
      let result = job;
      if (job.state !== 'done') {
        onStart(eps);
        follow = followJob(job.job, (p) => {
          if (mine === token) setProgress(p.progress, p.stage);
        });
        result = await follow.done;
        if (mine !== token) return;
      }
      markFitted(fitName, eps);
      showFacts({
        votCount: Number.isFinite(Number(result.votCount)) ? Number(result.votCount) : undefined,
        fitSeconds: Number.isFinite(Number(result.fitSeconds)) ? Number(result.fitSeconds) : undefined,
      });
      banner.clear('fit');
      onReady(eps, { refitted: true });
    } catch (e) {
      if (mine !== token) return;
      if (e.status === 403) {
        // A viewer's token starts no fit through POST /api/fit; the frames ask for eps themselves, which
        // the server draws at the default eps or one an operator has fitted, and refuses (shown) otherwise.
        banner.clear('fit');
        onReady(eps);
        return;
      }
      banner.show(e.message, 'fit');
    } finally {
      if (mine === token) {
        fitting = null;
        follow = null;
        progress.box.hidden = true;
        onChange();
      }
    }
  }

  return {
    ensure,
    // The fit being waited for, {eps, progress, stage}, or null.
    fitting: () => fitting,
  };
}
