// Refresher: redraws a view from its latest state, one redraw at a time.
// A change during a redraw asks for one more, so what is drawn last is
// always the latest state, and `settled` resolves once it is. A redraw that
// failed reports its error; the next one that succeeds reports null.

export class Refresher {
  // `redraw` is an async function; `report` gets what it throws, or null
  // when it succeeds.
  constructor(redraw, report) {
    this.redraw = redraw;
    this.report = report;
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
        if (!this.again) this.report(null);
      } catch (error) {
        if (!this.again) this.report(error);
      }
    } while (this.again);
    this.running = null;
  }

  // superseded is true while a redraw runs for a state that has changed
  // since it began (its drawing would be stale).
  get superseded() {
    return this.again;
  }

  // settled resolves once the latest state is drawn.
  async settled() {
    while (this.running) await this.running;
  }
}
