// The playground page's entry (bundled with three.js into /playground.js):
// wires the curve view and the surface view to the page, shows the server's
// errors in the status line, and exposes both views as window.playground
// for tests (tests/browser/playground_test.mjs) and the curious.

import {CurveView} from './curves.js';
import {whenNoCalls} from './rpc.js';
import {SurfaceView} from './surfaces.js';

const status = document.querySelector('#status');

function report(error) {
  status.textContent = error.code ? `${error.code}: ${error.message}` : String(error.message ?? error);
  status.classList.add('error');
}

function clearReport() {
  status.textContent = 'Every number here is an answer of freeformd.';
  status.classList.remove('error');
}

const curves = new CurveView(document.querySelector('#curves'), report);
const surfaces = new SurfaceView(document.querySelector('#surfaces'), report);
for (const control of document.querySelectorAll('[data-control]')) {
  control.addEventListener('input', clearReport);
  control.addEventListener('click', clearReport);
}

window.playground = {
  curves,
  surfaces,
  // idle resolves once both views have drawn their latest state.
  async idle() {
    do {
      await Promise.all([curves.settled(), surfaces.settled()]);
      await whenNoCalls();
    } while (curves.refresher.running || surfaces.refresher.running);
  },
};

curves.refresh();
surfaces.refresh();
