#include "svg_drawing.h"

#include <algorithm>
#include <limits>

namespace freeform::cli {

void SvgDrawing::AddPolyline(absl::Span<const double> points, int dimension,
                             const Style& style) {
  Polyline polyline{.xy = {}, .style = style};
  if (dimension < 1) return;
  const size_t dim = static_cast<size_t>(dimension);
  for (size_t i = 0; i + dim <= points.size(); i += dim) {
    polyline.xy.push_back(points[i]);
    polyline.xy.push_back(dim > 1 ? points[i + 1] : 0.0);
  }
  polylines_.push_back(std::move(polyline));
}

void SvgDrawing::Write(std::ostream& out, double size) const {
  double lo_x = std::numeric_limits<double>::infinity(), hi_x = -lo_x;
  double lo_y = lo_x, hi_y = -lo_x;
  for (const Polyline& polyline : polylines_) {
    for (size_t i = 0; i < polyline.xy.size(); i += 2) {
      lo_x = std::min(lo_x, polyline.xy[i]);
      hi_x = std::max(hi_x, polyline.xy[i]);
      lo_y = std::min(lo_y, polyline.xy[i + 1]);
      hi_y = std::max(hi_y, polyline.xy[i + 1]);
    }
  }
  if (!(lo_x <= hi_x)) lo_x = hi_x = lo_y = hi_y = 0;
  const double margin = 20;
  const double extent = std::max({hi_x - lo_x, hi_y - lo_y, 1e-300});
  const double scale = (size - 2 * margin) / extent;
  const double height = (hi_y - lo_y) * scale + 2 * margin;
  out << R"(<svg xmlns="http://www.w3.org/2000/svg" width=")" << size
      << R"(" height=")" << height << R"(">)"
      << "\n";
  out << R"(<rect width="100%" height="100%" fill="white"/>)"
      << "\n";
  for (const Polyline& polyline : polylines_) {
    const Style& style = polyline.style;
    out << (style.closed ? "<polygon" : "<polyline")
        << R"( fill="none" stroke=")" << style.color << R"(" stroke-width=")"
        << style.width << '"'
        << (style.dashed ? R"( stroke-dasharray="6 4")" : "") << R"( points=")";
    std::string dots;
    for (size_t i = 0; i < polyline.xy.size(); i += 2) {
      const double x = margin + (polyline.xy[i] - lo_x) * scale;
      const double y = margin + (hi_y - polyline.xy[i + 1]) * scale;
      out << x << "," << y << " ";
      if (style.dots) {
        dots += "<circle cx=\"" + std::to_string(x) + "\" cy=\"" +
                std::to_string(y) + "\" r=\"3\" fill=\"" + style.color +
                "\"/>\n";
      }
    }
    out << "\"/>\n" << dots;
  }
  out << "</svg>\n";
}

}  // namespace freeform::cli
