#include "svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace hexlod::apps {
namespace {

constexpr double kWidth = 720, kHeight = 420, kLeft = 70, kRight = 180, kTop = 40, kBottom = 50;
const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                          "#9467bd", "#8c564b", "#e377c2", "#17becf"};

std::string escape(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '&')
            out += "&amp;";
        else if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else
            out += c;
    }
    return out;
}

// A "nice" tick step (1, 2 or 5 times a power of ten) for about five ticks over the span.
double tickStep(double span) {
    if (!(span > 0.0)) return 1.0;
    const double raw = span / 5.0, power = std::pow(10.0, std::floor(std::log10(raw)));
    const double fraction = raw / power;
    return (fraction < 1.5 ? 1.0 : fraction < 3.5 ? 2.0 : fraction < 7.5 ? 5.0 : 10.0) * power;
}

} // namespace

bool writeSvgPlot(const std::string& path, const std::string& title, const std::string& xLabel,
                  const std::string& yLabel, const std::vector<PlotSeries>& series, std::string& error) {
    double x0 = std::numeric_limits<double>::max(), x1 = -x0, y0 = x0, y1 = -x0;
    for (const PlotSeries& s : series) {
        for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
            if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
            x0 = std::min(x0, s.x[i]), x1 = std::max(x1, s.x[i]);
            y0 = std::min(y0, s.y[i]), y1 = std::max(y1, s.y[i]);
        }
    }
    if (x0 > x1) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
    if (x1 == x0) x1 = x0 + 1;
    y0 = std::min(y0, 0.0);
    if (y1 == y0) y1 = y0 + 1;
    const double xStep = tickStep(x1 - x0), yStep = tickStep(y1 - y0);
    x0 = std::floor(x0 / xStep) * xStep, x1 = std::ceil(x1 / xStep) * xStep;
    y1 = std::ceil(y1 / yStep) * yStep;
    const double plotW = kWidth - kLeft - kRight, plotH = kHeight - kTop - kBottom;
    auto px = [&](double x) { return kLeft + (x - x0) / (x1 - x0) * plotW; };
    auto py = [&](double y) { return kTop + plotH - (y - y0) / (y1 - y0) * plotH; };

    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" "
           "fill=\"white\"/>\n";
    svg << "<text x=\"" << kLeft << "\" y=\"24\" font-size=\"15\">" << escape(title) << "</text>\n";
    for (double x = x0; x <= x1 + xStep * 0.5; x += xStep) {
        svg << "<line x1=\"" << px(x) << "\" y1=\"" << kTop << "\" x2=\"" << px(x) << "\" y2=\""
            << kTop + plotH << "\" stroke=\"#eee\"/><text x=\"" << px(x) << "\" y=\"" << kTop + plotH + 16
            << "\" text-anchor=\"middle\">" << x << "</text>\n";
    }
    for (double y = y0; y <= y1 + yStep * 0.5; y += yStep) {
        svg << "<line x1=\"" << kLeft << "\" y1=\"" << py(y) << "\" x2=\"" << kLeft + plotW << "\" y2=\""
            << py(y) << "\" stroke=\"#eee\"/><text x=\"" << kLeft - 6 << "\" y=\"" << py(y) + 4
            << "\" text-anchor=\"end\">" << y << "</text>\n";
    }
    svg << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << plotW << "\" height=\"" << plotH
        << "\" fill=\"none\" stroke=\"#333\"/>\n";
    svg << "<text x=\"" << kLeft + plotW / 2 << "\" y=\"" << kHeight - 12 << "\" text-anchor=\"middle\">"
        << escape(xLabel) << "</text>\n";
    svg << "<text transform=\"translate(16," << kTop + plotH / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
        << escape(yLabel) << "</text>\n";
    for (size_t k = 0; k < series.size(); ++k) {
        const PlotSeries& s = series[k];
        const char* colour = kColours[k % 8];
        if (s.points) {
            for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
                if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
                    svg << "<circle cx=\"" << px(s.x[i]) << "\" cy=\"" << py(s.y[i]) << "\" r=\"4\" fill=\""
                        << colour << "\"/>\n";
        } else {
            svg << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\" points=\"";
            for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
                if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
                    svg << px(s.x[i]) << "," << py(s.y[i]) << " ";
            svg << "\"/>\n";
        }
        const double ly = kTop + 14 + 18.0 * double(k);
        svg << "<rect x=\"" << kLeft + plotW + 12 << "\" y=\"" << ly - 9
            << "\" width=\"12\" height=\"12\" fill=\"" << colour << "\"/><text x=\"" << kLeft + plotW + 30
            << "\" y=\"" << ly + 1 << "\">" << escape(s.name) << "</text>\n";
    }
    svg << "</svg>\n";
    std::ofstream out(path);
    out << svg.str();
    if (!out) {
        error = path + ": cannot write the plot";
        return false;
    }
    return true;
}

} // namespace hexlod::apps
