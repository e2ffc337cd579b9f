// The query subcommands' answers as CSV on stdout (--format csv): one row
// per closest point, arc-length sample or curvature point, with a header.
// Each returns the exit status.
#ifndef FREEFORM_CLIENT_CLI_QUERY_CSV_H_
#define FREEFORM_CLIENT_CLI_QUERY_CSV_H_

#include "freeform/v1/curve_service.pb.h"
#include "freeform/v1/surface_service.pb.h"

namespace freeform::cli {

// closest: query, distance, t (or u, v), x0, x1, ... per minimum.
int PrintClosestCsv(const v1::ClosestPointResponse& response);
// sample-length: t, x0, x1, ... per sample.
int PrintSamplesCsv(const v1::SampleByArcLengthResponse& response);
// curvature: index, curvature, [torsion,] status, tangent, normal[,
// binormal] per parameter.
int PrintCurveCurvatureCsv(const v1::CurveCurvatureResponse& response);
// curvature --surface: index, gaussian, mean, k1, k2, status, normal and
// principal directions per point.
int PrintSurfaceCurvatureCsv(const v1::SurfaceCurvatureResponse& response);

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_QUERY_CSV_H_
