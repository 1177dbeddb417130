// A scatter plot as SVG on log-log axes (error against time), points coloured by the group of the
// setting they belong to, the Pareto front drawn as a line through its labelled points.
#pragma once

#include <string>
#include <vector>

namespace vitrum::study {

struct PlotPoint {
    double x = 0;  // > 0
    double y = 0;  // > 0; points with y <= 0 (no error at all) are drawn on the bottom edge
    int group = 0;  // index into PlotSpec::groups
    std::string label;  // drawn next to the point when it is on the front
};

struct PlotSpec {
    std::string title;
    std::string xLabel;
    std::string yLabel;
    std::vector<std::string> groups;
    std::vector<PlotPoint> points;
    std::vector<std::size_t> front;  // indices into points, in x order
};

std::string scatterSvg(const PlotSpec& spec);

}  // namespace vitrum::study
