#include "study/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace vitrum::study {
namespace {

constexpr double kWidth = 760, kHeight = 480;
constexpr double kLeft = 78, kRight = 210, kTop = 40, kBottom = 56;  // margins; the legend sits right
const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

std::string number(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f", v);
    return buffer;
}

std::string escape(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '&') out += "&amp;";
        else out += c;
    }
    return out;
}

std::string decadeLabel(int exponent) {
    if (exponent >= 0 && exponent <= 3) return std::to_string(int(std::pow(10, exponent) + 0.5));
    if (exponent >= -3 && exponent < 0) {
        std::string s = "0.";
        for (int i = -1; i > exponent; --i) s += '0';
        return s + "1";
    }
    return "1e" + std::to_string(exponent);
}

struct LogAxis {
    double lo = 0, hi = 1;  // decades (log10) spanned
    double from = 0, to = 1;  // pixels
    double map(double v) const { return from + (std::log10(v) - lo) / (hi - lo) * (to - from); }
};

LogAxis axisFor(const std::vector<double>& values, double from, double to) {
    double lo = 1e300, hi = -1e300;
    for (double v : values)
        if (v > 0) lo = std::min(lo, v), hi = std::max(hi, v);
    if (lo > hi) lo = hi = 1;
    LogAxis axis;
    axis.lo = std::floor(std::log10(lo));
    axis.hi = std::ceil(std::log10(hi));
    if (axis.hi <= axis.lo) axis.hi = axis.lo + 1;
    axis.from = from;
    axis.to = to;
    return axis;
}

}  // namespace

std::string scatterSvg(const PlotSpec& spec) {
    std::vector<double> xs, ys;
    for (const PlotPoint& p : spec.points) xs.push_back(p.x), ys.push_back(p.y);
    const LogAxis x = axisFor(xs, kLeft, kWidth - kRight);
    const LogAxis y = axisFor(ys, kHeight - kBottom, kTop);
    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        << "<text x=\"" << kLeft << "\" y=\"22\" font-size=\"15\">" << escape(spec.title) << "</text>\n";
    // Grid and decade ticks.
    for (int e = int(x.lo); e <= int(x.hi); ++e) {
        const double px = x.map(std::pow(10.0, e));
        svg << "<line x1=\"" << number(px) << "\" y1=\"" << kTop << "\" x2=\"" << number(px) << "\" y2=\""
            << kHeight - kBottom << "\" stroke=\"#ddd\"/>\n<text x=\"" << number(px) << "\" y=\""
            << kHeight - kBottom + 16 << "\" text-anchor=\"middle\">" << decadeLabel(e) << "</text>\n";
    }
    for (int e = int(y.lo); e <= int(y.hi); ++e) {
        const double py = y.map(std::pow(10.0, e));
        svg << "<line x1=\"" << kLeft << "\" y1=\"" << number(py) << "\" x2=\"" << kWidth - kRight << "\" y2=\""
            << number(py) << "\" stroke=\"#ddd\"/>\n<text x=\"" << kLeft - 6 << "\" y=\"" << number(py + 4)
            << "\" text-anchor=\"end\">" << decadeLabel(e) << "</text>\n";
    }
    svg << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << kWidth - kLeft - kRight << "\" height=\""
        << kHeight - kTop - kBottom << "\" fill=\"none\" stroke=\"#444\"/>\n"
        << "<text x=\"" << (kLeft + kWidth - kRight) / 2 << "\" y=\"" << kHeight - 14 << "\" text-anchor=\"middle\">"
        << escape(spec.xLabel) << "</text>\n"
        << "<text transform=\"translate(18," << (kTop + kHeight - kBottom) / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
        << escape(spec.yLabel) << "</text>\n";
    auto position = [&](const PlotPoint& p) {
        const double py = p.y > 0 ? y.map(p.y) : kHeight - kBottom;
        return std::pair<double, double>(x.map(p.x), py);
    };
    // The front first, under the points.
    if (!spec.front.empty()) {
        svg << "<polyline fill=\"none\" stroke=\"#000\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\" points=\"";
        for (std::size_t i : spec.front) {
            const auto [px, py] = position(spec.points[i]);
            svg << number(px) << "," << number(py) << " ";
        }
        svg << "\"/>\n";
    }
    for (const PlotPoint& p : spec.points) {
        const auto [px, py] = position(p);
        svg << "<circle cx=\"" << number(px) << "\" cy=\"" << number(py) << "\" r=\"4\" fill=\""
            << kColours[p.group % 8] << "\" fill-opacity=\"0.8\"/>\n";
    }
    for (std::size_t i : spec.front) {
        const auto [px, py] = position(spec.points[i]);
        svg << "<circle cx=\"" << number(px) << "\" cy=\"" << number(py)
            << "\" r=\"6.5\" fill=\"none\" stroke=\"#000\"/>\n<text x=\"" << number(px + 8) << "\" y=\"" << number(py - 6)
            << "\" font-size=\"10\">" << escape(spec.points[i].label) << "</text>\n";
    }
    // Legend.
    double ly = kTop + 10;
    for (std::size_t g = 0; g < spec.groups.size(); ++g, ly += 20) {
        svg << "<circle cx=\"" << kWidth - kRight + 22 << "\" cy=\"" << ly << "\" r=\"5\" fill=\"" << kColours[g % 8]
            << "\"/>\n<text x=\"" << kWidth - kRight + 34 << "\" y=\"" << ly + 4 << "\">" << escape(spec.groups[g])
            << "</text>\n";
    }
    svg << "<circle cx=\"" << kWidth - kRight + 22 << "\" cy=\"" << ly << "\" r=\"6.5\" fill=\"none\" stroke=\"#000\"/>\n"
        << "<text x=\"" << kWidth - kRight + 34 << "\" y=\"" << ly + 4 << "\">Pareto front</text>\n</svg>\n";
    return svg.str();
}

}  // namespace vitrum::study
