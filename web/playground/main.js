// The playground page's entry (bundled with three.js into /playground.js):
// wires the curve view and the surface view to the page, shows the server's
// errors in the status line, and exposes both views as window.playground
// for tests (tests/browser/playground_test.mjs) and the curious.

import {CurveView} from './curves.js';
import {callsPending, whenNoCalls} from './rpc.js';
import {SurfaceView} from './surfaces.js';

const status = document.querySelector('#status');

// report shows a server's error in the status line, or clears it (null).
function report(error) {
  status.classList.toggle('error', Boolean(error));
  if (!error) {
    status.textContent = 'Every number here is an answer of freeformd.';
  } else {
    status.textContent = error.code ? `${error.code}: ${error.message}` : String(error.message ?? error);
  }
}

const curves = new CurveView(document.querySelector('#curves'), report);
const surfaces = new SurfaceView(document.querySelector('#surfaces'), report);

window.playground = {
  curves,
  surfaces,
  // idle resolves once both views have drawn their latest state: no redraw
  // and no call in flight, still so after the continuations of the last
  // answers have run (a button's action redraws when its call returns).
  async idle() {
    const busy = () => curves.refresher.running || surfaces.refresher.running || callsPending() > 0;
    do {
      await Promise.all([curves.settled(), surfaces.settled()]);
      await whenNoCalls();
      await new Promise((resolve) => setTimeout(resolve, 0));
    } while (busy());
  },
};

curves.refresh();
surfaces.refresh();
