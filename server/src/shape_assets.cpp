#include "hexlod/server/shape_assets.h"

#include <unordered_set>

namespace hexlod::server {
namespace {

template <typename T>
const T* lookup(const std::vector<std::vector<std::optional<T>>>& table, uint32_t grammar, uint32_t shape) {
    if (grammar >= table.size() || shape >= table[grammar].size() || !table[grammar][shape]) return nullptr;
    return &*table[grammar][shape];
}

// Shapes of one name and declaration in several grammars share their bytes: counted once.
void count(const AssetBytes& bytes, std::unordered_set<const void*>& seen, uint64_t& total) {
    if (bytes && seen.insert(bytes.get()).second) total += bytes->size();
}

} // namespace

const MeshAsset* ShapeAssets::mesh(uint32_t grammar, uint32_t shape) const {
    return lookup(meshes, grammar, shape);
}

const ImpostorAsset* ShapeAssets::impostor(uint32_t grammar, uint32_t shape) const {
    return lookup(impostors, grammar, shape);
}

uint64_t ShapeAssets::byteSize() const {
    uint64_t bytes = 0;
    std::unordered_set<const void*> seen;
    for (const auto& list : meshes)
        for (const auto& m : list)
            if (m) {
                count(m->glb, seen, bytes);
                if (m->coarse) count(m->coarse->glb, seen, bytes);
            }
    auto files = [&](const ImpostorAsset& i) {
        for (const AssetBytes* b : {&i.albedoPng, &i.normalPng, &i.exr}) count(*b, seen, bytes);
    };
    for (const auto& list : impostors)
        for (const auto& i : list)
            if (i) files(*i);
    for (const SpeciesAsset& s : species) files(s.impostor);
    return bytes;
}

} // namespace hexlod::server
