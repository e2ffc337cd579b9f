// Calls freeformd from Node with @grpc/grpc-js and @grpc/proto-loader.
//
// Evaluates the cubic Bezier curve (0,0), (1,2), (3,2), (4,0) (unary and
// streamed), tessellates the NURBS unit circle, and sends a bad request to
// show how the google.rpc.BadRequest of an INVALID_ARGUMENT is decoded.
//
//   mkdir -p build/node && cp examples/node/package.json build/node/
//   npm install --prefix build/node
//   NODE_PATH=build/node/node_modules node examples/node/freeform_example.js \
//       --address 127.0.0.1:50051
//
// Each answer is printed as a CSV table under a "# <RPC>" line; numbers are
// JavaScript's String() of the doubles (the shortest text that reads back as
// the same double). --protos DIR names the repository's proto/ folder when
// this file is run from elsewhere.
'use strict';

const fs = require('fs');
const path = require('path');
const grpc = require('@grpc/grpc-js');
const protoLoader = require('@grpc/proto-loader');
const protobuf = require('protobufjs');

// gRPC clients refuse answers over 4 MB by default; a large tessellation or
// batch needs more (or the *Stream RPCs, whose chunks stay small).
const CHANNEL_OPTIONS = {'grpc.max_receive_message_length': 64 * 1024 * 1024};
const TIMEOUT_MS = 10000;

const CUBIC = [0, 0, 1, 2, 3, 2, 4, 0];

function parseArgs(argv) {
  const args = {
    address: '127.0.0.1:50051',
    protos: path.resolve(__dirname, '..', '..', 'proto'),
  };
  for (let i = 0; i < argv.length; i += 2) {
    const name = argv[i].replace(/^--/, '');
    if (!(name in args) || i + 1 >= argv.length) {
      throw new Error(`usage: freeform_example.js [--address HOST:PORT] ` +
                      `[--protos PROTO_DIR]`);
    }
    args[name] = argv[i + 1];
  }
  return args;
}

// The include roots are proto/ and proto/third_party/. keepCase keeps the
// .proto field names (control_points): without it proto-loader expects
// camelCase and silently drops the snake_case fields of a request.
function loaderOptions(protoDir) {
  return {
    keepCase: true,
    longs: String,
    enums: String,
    defaults: true,
    oneofs: true,
    includeDirs: [protoDir, path.join(protoDir, 'third_party')],
  };
}

// google.rpc.Status and BadRequest, to decode grpc-status-details-bin.
function loadErrorTypes(includeDirs) {
  const root = new protobuf.Root();
  root.resolvePath = (origin, target) =>
    includeDirs.map((dir) => path.join(dir, target))
        .find((file) => fs.existsSync(file)) || target;
  root.loadSync(['google/rpc/status.proto', 'google/rpc/error_details.proto'],
                {keepCase: true});
  return {
    status: root.lookupType('google.rpc.Status'),
    badRequest: root.lookupType('google.rpc.BadRequest'),
  };
}

function bezierCurve(coordinates) {
  return {bezier: {control_points: {dimension: 2, coordinates}}};
}

// The NURBS unit circle of examples/nurbs_circle_polyline.json.
function unitCircle() {
  const w = Math.sqrt(0.5);
  return {
    bspline: {
      degree: 2,
      control_points: {
        dimension: 2,
        coordinates: [1, 0, 1, 1, 0, 1, -1, 1, -1, 0, -1, -1, 0, -1, 1, -1,
                      1, 0],
      },
      knots: [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1],
      weights: [1, w, 1, w, 1, w, 1, w, 1],
    },
  };
}

function unary(client, method, request) {
  const deadline = Date.now() + TIMEOUT_MS;
  return new Promise((resolve, reject) => {
    client[method](request, {deadline}, (error, response) => {
      if (error) reject(error);
      else resolve(response);
    });
  });
}

function header(dimension, derivativeOrder) {
  const names = ['index'];
  for (let k = 0; k <= derivativeOrder; ++k) {
    for (let j = 0; j < dimension; ++j) {
      names.push(`${k === 0 ? 'x' : `d${k}x`}${j}`);
    }
  }
  return names.join(',');
}

// One CSV row per parameter: index, then each derivative's point.
function printSamples(firstIndex, response) {
  const dimension = response.dimension;
  for (let i = 0; i < response.count; ++i) {
    const row = [String(firstIndex + i)];
    for (const derivative of response.derivatives) {
      row.push(...derivative.coordinates
                   .slice(i * dimension, (i + 1) * dimension).map(String));
    }
    console.log(row.join(','));
  }
}

async function evaluate(client) {
  const response = await unary(client, 'Evaluate', {
    curve: bezierCurve(CUBIC),
    parameters: {list: {values: [0, 0.5, 1]}},
    derivative_order: 1,
  });
  console.log('# CurveService.Evaluate');
  console.log(header(response.dimension, 1));
  printSamples(0, response);
}

async function evaluateStream(client) {
  // Nine parameters 0, 1/8, ..., 1 (the whole domain), four per chunk.
  const call = client.EvaluateStream(
      {
        curve: bezierCurve(CUBIC),
        parameters: {range: {count: 9}},
        chunk_size: 4,
      },
      {deadline: Date.now() + TIMEOUT_MS});
  const chunks = [];
  for await (const chunk of call) chunks.push(chunk);
  console.log('# CurveService.EvaluateStream chunks');
  console.log('first_index,count');
  // uint64 fields arrive as strings (longs: String).
  for (const chunk of chunks) {
    console.log(`${chunk.first_index},${chunk.count}`);
  }
  console.log('# CurveService.EvaluateStream');
  console.log(header(chunks[0].dimension, 0));
  for (const chunk of chunks) printSamples(Number(chunk.first_index), chunk);
}

async function tessellate(client) {
  const response = await unary(client, 'Tessellate', {
    curve: unitCircle(),
    tolerance: 0.001,
  });
  const {dimension, coordinates} = response.points;
  console.log('# CurveService.Tessellate');
  console.log('index,t,x0,x1');
  response.parameters.forEach((t, i) => {
    const x = coordinates.slice(i * dimension, (i + 1) * dimension);
    console.log([i, t, ...x].map(String).join(','));
  });
}

// The field violations of the google.rpc.Status in the error's trailer.
function badRequestViolations(error, errorTypes) {
  const violations = [];
  for (const bytes of error.metadata.get('grpc-status-details-bin')) {
    const status = errorTypes.status.decode(bytes);
    for (const detail of status.details) {
      if (detail.type_url === 'type.googleapis.com/google.rpc.BadRequest') {
        violations.push(
            ...errorTypes.badRequest.decode(detail.value).field_violations);
      }
    }
  }
  return violations;
}

async function invalidArgument(client, errorTypes) {
  try {
    // Three coordinates cannot be points of dimension 2.
    await unary(client, 'Evaluate', {
      curve: bezierCurve([0, 0, 1]),
      parameters: {list: {values: [0.5]}},
    });
  } catch (error) {
    if (error.code === undefined) throw error;
    console.log('# INVALID_ARGUMENT');
    console.log(`status ${grpc.status[error.code]}: ${error.details}`);
    for (const violation of badRequestViolations(error, errorTypes)) {
      console.log(`field ${violation.field}: ${violation.description}`);
    }
    return error.code === grpc.status.INVALID_ARGUMENT;
  }
  console.error('error: the bad request was accepted');
  return false;
}

async function main() {
  const args = parseArgs(process.argv.slice(2));
  const options = loaderOptions(args.protos);
  const definition =
      protoLoader.loadSync('freeform/v1/curve_service.proto', options);
  const v1 = grpc.loadPackageDefinition(definition).freeform.v1;
  const errorTypes = loadErrorTypes(options.includeDirs);
  const client = new v1.CurveService(
      args.address, grpc.credentials.createInsecure(), CHANNEL_OPTIONS);
  try {
    await evaluate(client);
    await evaluateStream(client);
    await tessellate(client);
    return (await invalidArgument(client, errorTypes)) ? 0 : 1;
  } catch (error) {
    if (error.code === undefined) throw error;
    console.error(`error: ${grpc.status[error.code]}: ${error.details}`);
    return 1;
  } finally {
    client.close();
  }
}

main().then((code) => {
  process.exitCode = code;
}, (error) => {
  console.error(error);
  process.exitCode = 1;
});
