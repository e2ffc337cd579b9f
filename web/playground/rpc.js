// The playground's one door to the server: Connect unary calls over the
// HTTP/JSON gateway (docs/http.md). Every number the page shows or draws
// comes back through here; the page computes none itself.

// RpcError carries a Connect error: its code and the server's message,
// which names the field at fault.
export class RpcError extends Error {
  constructor(code, message) {
    super(message);
    this.code = code;
  }
}

let callsInFlight = 0;
const idleWaiters = [];

// call POSTs `request` (proto3 JSON) to freeform.v1.SERVICE/METHOD and
// returns the answer's JSON; throws RpcError with the server's error.
export async function call(service, method, request) {
  callsInFlight++;
  try {
    const answer = await fetch(`/freeform.v1.${service}/${method}`, {
      method: 'POST',
      headers: {'Content-Type': 'application/json', 'Connect-Protocol-Version': '1'},
      body: JSON.stringify(request),
    });
    const body = await answer.json();
    if (!answer.ok) throw new RpcError(body.code, body.message);
    return body;
  } finally {
    callsInFlight--;
    if (callsInFlight === 0) idleWaiters.splice(0).forEach((resolve) => resolve());
  }
}

// callsPending returns the number of calls in flight.
export function callsPending() {
  return callsInFlight;
}

// whenNoCalls resolves once no call is in flight.
export function whenNoCalls() {
  if (callsInFlight === 0) return Promise.resolve();
  return new Promise((resolve) => idleWaiters.push(resolve));
}

// pointsOf returns the [x, y, ...] points of a Points message.
export function pointsOf(message) {
  const coordinates = message?.coordinates ?? [];
  const dimension = message?.dimension ?? 1;
  const points = [];
  for (let start = 0; start < coordinates.length; start += dimension) {
    points.push(coordinates.slice(start, start + dimension));
  }
  return points;
}

// pointsMessage returns the Points message of 2D or 3D points.
export function pointsMessage(points) {
  return {dimension: points[0]?.length ?? 2, coordinates: points.flat()};
}
