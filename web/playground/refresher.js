// Refresher: redraws a view from its latest state, one redraw at a time.
// A change during a redraw asks for one more, so what is drawn last is
// always the latest state, and `settled` resolves once it is.

export class Refresher {
  // `redraw` is an async function; `onError` gets what it throws.
  constructor(redraw, onError) {
    this.redraw = redraw;
    this.onError = onError;
    this.running = null;
    this.again = false;
  }

  // request asks for a redraw of the state as it is now.
  request() {
    if (this.running) {
      this.again = true;
      return;
    }
    this.running = this.run();
  }

  async run() {
    do {
      this.again = false;
      try {
        await this.redraw();
      } catch (error) {
        this.onError(error);
      }
    } while (this.again);
    this.running = null;
  }

  // settled resolves once the latest state is drawn.
  async settled() {
    while (this.running) await this.running;
  }
}
