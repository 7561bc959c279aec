// Minimal SVG charts for benchmark reports (frame time along a walk, error against time):
// linear axes with ticks, one polyline or point set per series, a legend. Plain text, no
// plotting dependency.
#pragma once

#include <string>
#include <vector>

namespace hexlod::apps {

struct PlotSeries {
    std::string name;
    std::vector<double> x, y;
    bool points = false; // markers instead of a line
};

bool writeSvgPlot(const std::string& path, const std::string& title, const std::string& xLabel,
                  const std::string& yLabel, const std::vector<PlotSeries>& series, std::string& error);

} // namespace hexlod::apps
