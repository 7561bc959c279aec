// Nearest views through FLANN's single kd-tree index, exact (unbounded checks).
#include "hexlod/impostor/view_lookup.h"

#include <flann/flann.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hexlod::impostor {

struct ViewLookup::Index {
    flann::Matrix<float> dataset;
    flann::Index<flann::L2_Simple<float>> tree;
    explicit Index(flann::Matrix<float> data) : dataset(data), tree(data, flann::KDTreeSingleIndexParams(4)) {
        tree.buildIndex();
    }
};

ViewLookup::ViewLookup(const ViewLayout& layout) : layout_(layout) {
    directions_.reserve(size_t(layout.viewCount()) * 3);
    for (uint32_t v = 0; v < layout.viewCount(); ++v) {
        glm::vec3 d = layout.direction(v);
        directions_.insert(directions_.end(), {d.x, d.y, d.z});
    }
    index_ = std::make_unique<Index>(flann::Matrix<float>(directions_.data(), layout.viewCount(), 3));
}

ViewLookup::~ViewLookup() = default;
ViewLookup::ViewLookup(ViewLookup&&) noexcept = default;
ViewLookup& ViewLookup::operator=(ViewLookup&&) noexcept = default;

bool ViewLookup::nearestViews(const glm::vec3& direction, ViewWeights& out) const {
    out = {};
    if (!std::isfinite(direction.x) || !std::isfinite(direction.y) || !std::isfinite(direction.z))
        return false;
    // Scale by the largest component first, so a tiny direction does not underflow to zero.
    float largest = std::max({std::abs(direction.x), std::abs(direction.y), std::abs(direction.z)});
    if (!(largest > 0.0f)) return false;
    glm::vec3 d = glm::normalize(direction / largest);
    if (layout_.sphere == ViewSphere::Hemisphere && d.z < 0.0f) {
        d.z = 0.0f;
        float rim = glm::length(d);
        d = rim > 1e-6f ? d / rim : glm::vec3(0.0f, 0.0f, 1.0f);
    }
    const uint32_t views = layout_.viewCount();
    const uint32_t wanted = std::min<uint32_t>(5, views);
    std::array<size_t, 5> indices{};
    std::array<float, 5> squared{};
    flann::Matrix<float> query(&d.x, 1, 3);
    flann::Matrix<size_t> indexMatrix(indices.data(), 1, wanted);
    flann::Matrix<float> distanceMatrix(squared.data(), 1, wanted);
    index_->tree.knnSearch(query, indexMatrix, distanceMatrix, wanted,
                           flann::SearchParams(flann::FLANN_CHECKS_UNLIMITED));

    const uint32_t blended = std::min<uint32_t>(4, wanted);
    for (uint32_t i = 0; i < 4; ++i) out.views[i] = uint32_t(indices[std::min(i, blended - 1)]);
    // A direction on (or within float noise of) a view: that view alone.
    constexpr float kExact = 1e-6f;
    float nearest = std::sqrt(std::max(squared[0], 0.0f));
    if (nearest < kExact) {
        out.weights = {1.0f, 0.0f, 0.0f, 0.0f};
        out.count = 1;
        return true;
    }
    float cutoff = wanted > 4 ? 1.0f / std::sqrt(squared[4]) : 0.0f;
    float total = 0.0f;
    for (uint32_t i = 0; i < blended; ++i) {
        float distance = std::sqrt(std::max(squared[i], 0.0f));
        out.weights[i] = std::max(0.0f, 1.0f / distance - cutoff);
        total += out.weights[i];
    }
    if (!(total > 0.0f)) {
        // Four views tied with the fifth: equal shares keep the sum at 1.
        for (uint32_t i = 0; i < blended; ++i) out.weights[i] = 1.0f / float(blended);
        total = 1.0f;
    }
    // Each share less the floor: a view drops out where its share falls to the floor, so the
    // weights stay continuous, and the nearest view's share (at least a quarter) keeps some.
    float kept = 0.0f;
    for (uint32_t i = 0; i < blended; ++i) {
        out.weights[i] = std::max(0.0f, out.weights[i] / total - kMinViewShare);
        kept += out.weights[i];
    }
    out.count = 0;
    for (uint32_t i = 0; i < blended; ++i) {
        out.weights[i] /= kept;
        out.count += out.weights[i] > 0.0f;
    }
    return true;
}

const ViewWeights& DirectionTable::at(const glm::vec3& direction) const {
    glm::vec3 d = direction;
    glm::vec2 p;
    if (sphere == ViewSphere::Hemisphere) {
        d.z = std::max(d.z, 0.0f);
        if (d.x == 0.0f && d.y == 0.0f && d.z == 0.0f) d.z = 1.0f;
        p = encodeHemiOctahedral(d);
    } else {
        p = encodeOctahedral(d);
    }
    glm::vec2 position = p * 0.5f + 0.5f;
    int x = std::clamp(int(position.x * float(resolution)), 0, int(resolution) - 1);
    int y = std::clamp(int(position.y * float(resolution)), 0, int(resolution) - 1);
    return texels[size_t(y) * resolution + size_t(x)];
}

DirectionTable ViewLookup::buildTable(uint32_t resolution) const {
    if (resolution == 0 || resolution > 1024) {
        throw std::invalid_argument("direction table resolution " + std::to_string(resolution) +
                                    " is outside [1, 1024]");
    }
    DirectionTable table;
    table.resolution = resolution;
    table.sphere = layout_.sphere;
    table.texels.resize(size_t(resolution) * resolution);
    for (uint32_t y = 0; y < resolution; ++y) {
        for (uint32_t x = 0; x < resolution; ++x) {
            glm::vec2 p((float(x) + 0.5f) / float(resolution) * 2.0f - 1.0f,
                        (float(y) + 0.5f) / float(resolution) * 2.0f - 1.0f);
            glm::vec3 d =
                layout_.sphere == ViewSphere::Hemisphere ? decodeHemiOctahedral(p) : decodeOctahedral(p);
            nearestViews(d, table.texels[size_t(y) * resolution + x]);
        }
    }
    return table;
}

} // namespace hexlod::impostor
