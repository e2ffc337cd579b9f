// SvgDrawing (svg_drawing.h): polylines and segments fitted into an SVG.
#include "svg_drawing.h"

#include <algorithm>
#include <limits>

namespace freeform::cli {
namespace {

// The first two coordinates of each point (0 for a missing y).
std::vector<double> PlaneCoordinates(absl::Span<const double> points,
                                     int dimension) {
  std::vector<double> xy;
  if (dimension < 1) return xy;
  const size_t dim = static_cast<size_t>(dimension);
  for (size_t i = 0; i + dim <= points.size(); i += dim) {
    xy.push_back(points[i]);
    xy.push_back(dim > 1 ? points[i + 1] : 0.0);
  }
  return xy;
}

}  // namespace

void SvgDrawing::AddPolyline(absl::Span<const double> points, int dimension,
                             const Style& style) {
  if (dimension < 1) return;
  polylines_.push_back({.xy = PlaneCoordinates(points, dimension),
                        .style = style,
                        .segments = false});
}

void SvgDrawing::AddSegments(absl::Span<const double> from,
                             absl::Span<const double> to, int dimension,
                             const Style& style) {
  if (dimension < 1) return;
  const std::vector<double> starts = PlaneCoordinates(from, dimension);
  const std::vector<double> ends = PlaneCoordinates(to, dimension);
  Polyline segments{.xy = {}, .style = style, .segments = true};
  for (size_t i = 0; i + 1 < std::min(starts.size(), ends.size()); i += 2) {
    segments.xy.insert(segments.xy.end(),
                       {starts[i], starts[i + 1], ends[i], ends[i + 1]});
  }
  polylines_.push_back(std::move(segments));
}

SvgDrawing::Box SvgDrawing::Bounds() const {
  const double infinity = std::numeric_limits<double>::infinity();
  Box box{
      .lo_x = infinity, .hi_x = -infinity, .lo_y = infinity, .hi_y = -infinity};
  for (const Polyline& polyline : polylines_) {
    for (size_t i = 0; i < polyline.xy.size(); i += 2) {
      box.lo_x = std::min(box.lo_x, polyline.xy[i]);
      box.hi_x = std::max(box.hi_x, polyline.xy[i]);
      box.lo_y = std::min(box.lo_y, polyline.xy[i + 1]);
      box.hi_y = std::max(box.hi_y, polyline.xy[i + 1]);
    }
  }
  if (!(box.lo_x <= box.hi_x))
    box = {.lo_x = 0, .hi_x = 0, .lo_y = 0, .hi_y = 0};
  return box;
}

double SvgDrawing::Extent() const {
  const Box box = Bounds();
  return std::max(box.hi_x - box.lo_x, box.hi_y - box.lo_y);
}

void SvgDrawing::WriteElement(std::ostream& out, const Polyline& polyline,
                              const Frame& frame) {
  const Style& style = polyline.style;
  out << (polyline.segments ? "<path"
                            : (style.closed ? "<polygon" : "<polyline"));
  if (!style.label.empty()) out << R"( class=")" << style.label << '"';
  out << R"( fill="none" stroke=")" << style.color << R"(" stroke-width=")"
      << style.width << '"'
      << (style.dashed ? R"( stroke-dasharray="6 4")" : "")
      << (polyline.segments ? R"( d=")" : R"( points=")");
  std::string dots;
  for (size_t i = 0; i < polyline.xy.size(); i += 2) {
    const double x = frame.X(polyline.xy[i]);
    const double y = frame.Y(polyline.xy[i + 1]);
    if (polyline.segments) {
      out << (i % 4 == 0 ? "M" : "L") << x << " " << y << " ";
    } else {
      out << x << "," << y << " ";
    }
    if (style.dots) {
      dots += "<circle cx=\"" + std::to_string(x) + "\" cy=\"" +
              std::to_string(y) + "\" r=\"3\" fill=\"" + style.color + "\"/>\n";
    }
  }
  out << "\"/>\n" << dots;
}

void SvgDrawing::Write(std::ostream& out, double size) const {
  const Box box = Bounds();
  const double margin = 20;
  const double extent = std::max(Extent(), 1e-300);
  const Frame frame{
      .box = box, .margin = margin, .scale = (size - 2 * margin) / extent};
  const double height = (box.hi_y - box.lo_y) * frame.scale + 2 * margin;
  // The viewBox lets a viewer scale the picture to any size.
  out << R"(<svg xmlns="http://www.w3.org/2000/svg" width=")" << size
      << R"(" height=")" << height << R"(" viewBox="0 0 )" << size << " "
      << height << R"(">)"
      << "\n";
  out << R"(<rect width="100%" height="100%" fill="white"/>)"
      << "\n";
  for (const Polyline& polyline : polylines_) {
    WriteElement(out, polyline, frame);
  }
  out << "</svg>\n";
}

}  // namespace freeform::cli
