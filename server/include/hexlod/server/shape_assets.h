// What the service hands out per terminal shape besides batch content: the shape's mesh as
// .glb and, for shapes the scene's buildings emit, its impostor views (albedo PNG, normal and
// depth PNG, the EXR of the store); and per tree species with trees its full-sphere impostor,
// which clients draw as the species' billboard far from the camera. They are built once before the service
// starts serving (the app builds them with the render and lod modules, which need meshes and GL; the service
// itself stays free of both) and never change: parameter edits do not touch a shape's mesh,
// so every URL is content-addressed and immutable. Species are the one list that grows: the
// service takes them over on attach and adds those an edit makes (species_bakery.h).
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hexlod::server {

using AssetBytes = std::shared_ptr<const std::vector<uint8_t>>;

// A coarser mesh of a shape (lod/coarse_meshes.h): a client draws it instead of the shape's
// mesh at LOD4 where `deviation`, scaled by the terminal's scope, projects under the error
// bound, the rule of the native renderer's cull pass.
struct CoarseMeshAsset {
    uint64_t hash = 0; // its render::TerminalMesh::contentHash: the URL's key
    AssetBytes glb;
    std::array<float, 3> deviation{}; // render::meshDeviation from the shape's mesh, unit scope space
    uint32_t triangles = 0;
};

struct MeshAsset {
    uint64_t hash = 0; // render::TerminalMesh::contentHash: the URL's key
    AssetBytes glb;
    std::array<float, 3> nominalSize{1.0f, 1.0f, 1.0f};
    std::optional<CoarseMeshAsset> coarse;
};

struct ImpostorAsset {
    uint64_t key = 0;   // impostor::ImpostorAtlas::contentKey: the URL's key
    uint32_t layer = 0; // index among the scene's facade impostors (a texture array layer)
    std::array<float, 3> centre{}, boundsMin{}, boundsMax{};
    float radius = 1.0f;
    AssetBytes albedoPng; // sRGB colour, alpha = coverage
    AssetBytes normalPng; // rgb = shape-space normal * 0.5 + 0.5, alpha = depth * 0.5 + 0.5 (0: empty)
    AssetBytes exr;       // the store's file; null when baked without a store
};

// A tree species: the trees of tree grammar `grammar` whose parameters are exactly these
// floats (an edited tree matches none until the service has baked a species for its values).
struct SpeciesAsset {
    std::string name;
    uint32_t grammar = 0; // a tree grammar, scene order
    std::vector<float> parameters;
    ImpostorAsset impostor; // layer: the species index
    // A species baked for an edit that no tree has the values of any more, dropped to make
    // room for new ones: its files are gone (410) and the scene no longer lists it.
    bool retired = false;
};

struct ShapeAssets {
    // [grammar][shape] in the scene's grammar order; a missing entry is not served.
    std::vector<std::vector<std::optional<MeshAsset>>> meshes;
    std::vector<std::vector<std::optional<ImpostorAsset>>> impostors;
    // The facade view layout every impostor above shares (docs/protocol.md); null without any.
    nlohmann::json impostorLayout;
    std::vector<SpeciesAsset> species; // moved into the service on attach
    nlohmann::json speciesLayout;      // the full-sphere layout of every species impostor; null without
    bool meshesServed = false, impostorsServed = false, speciesServed = false;
    // What was built or left out and why, for /api/v1/scene's notes.
    std::vector<std::string> notes;

    const MeshAsset* mesh(uint32_t grammar, uint32_t shape) const;
    const ImpostorAsset* impostor(uint32_t grammar, uint32_t shape) const;
    uint64_t byteSize() const;
};

} // namespace hexlod::server
