// SvgDrawing: curves and control polygons as an SVG picture (for the CLI's
// --svg output). Points of any dimension are drawn by their first two
// coordinates, fitted into the picture with y pointing up. Not thread-safe.
#ifndef FREEFORM_CLIENT_CLI_SVG_DRAWING_H_
#define FREEFORM_CLIENT_CLI_SVG_DRAWING_H_

#include <ostream>
#include <string>
#include <vector>

#include "absl/types/span.h"

namespace freeform::cli {

class SvgDrawing {
 public:
  struct Style {
    std::string color = "black";
    double width = 1.5;
    bool dashed = false;
    bool dots = false;  // mark every point
    bool closed = false;
    // The element's class attribute (empty: none), to tell layers apart.
    std::string label;
  };

  // AddPolyline draws the points (dimension coordinates each) in order.
  void AddPolyline(absl::Span<const double> points, int dimension,
                   const Style& style);

  // AddSegments draws a line from each point of `from` to the point of `to`
  // with the same index (dimension coordinates each), as one path.
  void AddSegments(absl::Span<const double> from, absl::Span<const double> to,
                   int dimension, const Style& style);

  // Extent returns the larger side of the box of everything drawn so far
  // (0 when nothing is).
  double Extent() const;

  // Write prints the picture, `size` pixels wide.
  void Write(std::ostream& out, double size = 800) const;

 private:
  struct Polyline {
    std::vector<double> xy;
    Style style;
    bool segments = false;  // xy holds pairs of points, one line each
  };
  struct Box {
    double lo_x, hi_x, lo_y, hi_y;
  };
  // Where (x, y) lands in the picture.
  struct Frame {
    Box box;
    double margin;
    double scale;
    double X(double x) const { return margin + (x - box.lo_x) * scale; }
    double Y(double y) const { return margin + (box.hi_y - y) * scale; }
  };

  Box Bounds() const;
  static void WriteElement(std::ostream& out, const Polyline& polyline,
                           const Frame& frame);

  std::vector<Polyline> polylines_;
};

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_SVG_DRAWING_H_
