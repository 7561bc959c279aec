#include "serve_shape_assets.h"

#include "serve_species_bakery.h"
#include "shape_mesh_glb.h"

#include "hexlod/lod/coarse_meshes.h"
#include "hexlod/render/image_io.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

namespace hexlod::apps {
namespace {

using server::AssetBytes;

AssetBytes share(std::vector<uint8_t> bytes) {
    return std::make_shared<const std::vector<uint8_t>>(std::move(bytes));
}

std::array<float, 3> array3(const glm::vec3& v) {
    return {v.x, v.y, v.z};
}

nlohmann::json json3(const glm::vec3& v) {
    return {v.x, v.y, v.z};
}

// Every declared shape's mesh, and the coarse mesh of each shape that has one (the meshes the
// native renderer's cull pass picks between); shapes that share a mesh share its bytes.
void addMeshes(const cells::BatchCatalog& catalog, const render::TerminalMeshLibrary& library,
               server::ShapeAssets& assets) {
    std::map<const render::TerminalMesh*, AssetBytes> encoded;
    auto glb = [&](const render::TerminalMesh& mesh) {
        AssetBytes& bytes = encoded[&mesh];
        if (!bytes) bytes = share(shapeMeshGlb(mesh, mesh.shape));
        return bytes;
    };
    std::vector<std::pair<uint32_t, uint16_t>> globalShapes; // the ShapeTable's numbering
    assets.meshes.resize(library.grammarCount());
    for (uint32_t g = 0; g < library.grammarCount(); ++g) {
        for (uint16_t s = 0; s < library.shapeCount(g); ++s) {
            const render::TerminalMesh& mesh = library.mesh(g, s);
            assets.meshes[g].push_back(
                server::MeshAsset{mesh.contentHash, glb(mesh), array3(mesh.nominalSize), {}});
            globalShapes.emplace_back(g, s);
        }
    }
    const size_t fine = encoded.size();
    for (const lod::CoarseMesh& coarse : lod::coarseMeshes(catalog, library)) {
        const auto [g, s] = globalShapes.at(coarse.shape);
        assets.meshes[g][s]->coarse =
            server::CoarseMeshAsset{coarse.mesh->contentHash, glb(*coarse.mesh), array3(coarse.deviation),
                                    uint32_t(coarse.mesh->triangleCount())};
    }
    assets.meshesServed = true;
    const uint32_t grammars = library.grammarCount();
    assets.notes.push_back("terminal meshes (glTF): " + std::to_string(fine) + " distinct meshes for " +
                           std::to_string(grammars) + (grammars == 1 ? " grammar" : " grammars") +
                           ", unit scope space; " + std::to_string(encoded.size() - fine) + " coarse meshes");
}

// The normal-and-depth view as an 8-bit image: n * 0.5 + 0.5 and depth * 0.5 + 0.5, so an
// empty texel (depth -1) has alpha 0.
render::Image normalDepthImage(const render::Image& normalDepth) {
    render::Image out = normalDepth;
    for (float& v : out.pixels) v = v * 0.5f + 0.5f;
    return out;
}

AssetBytes readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return nullptr;
    return share(std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {}));
}

// The facade impostors' files, per (grammar, shape), and the tree species' files. False with a
// reason when one cannot be encoded.
bool addImpostors(const lod::SceneImpostors& baked, const std::string& storeDirectory,
                  server::ShapeAssets& assets, std::string& error) {
    std::optional<impostor::ImpostorStore> store;
    if (!storeDirectory.empty()) store.emplace(storeDirectory);
    std::vector<server::ImpostorAsset> layers(baked.facades.size());
    for (size_t i = 0; i < baked.facades.size(); ++i)
        if (!impostorAsset(baked.facades[i], uint32_t(i), store, layers[i], error)) return false;
    assets.impostors.resize(baked.facadeLayer.size());
    for (size_t g = 0; g < baked.facadeLayer.size(); ++g) {
        for (const int layer : baked.facadeLayer[g]) {
            assets.impostors[g].push_back(layer >= 0 ? std::optional(layers[size_t(layer)]) : std::nullopt);
        }
    }
    assets.impostorsServed = true;
    // The baker numbers species as it met them and skips one whose bake fails; only a complete
    // list pairs each atlas with its parameters, so anything else serves no species.
    if (baked.species.empty() || baked.species.size() != baked.speciesParameters.size()) return true;
    for (size_t s = 0; s < baked.species.size(); ++s) {
        server::SpeciesAsset species;
        const std::string& name = baked.species[s].shape; // "tree:<species>"
        species.name = name.rfind("tree:", 0) == 0 ? name.substr(5) : name;
        species.grammar = baked.speciesGrammar[s];
        species.parameters = baked.speciesParameters[s];
        if (!impostorAsset(baked.species[s], uint32_t(s), store, species.impostor, error)) return false;
        assets.species.push_back(std::move(species));
    }
    assets.speciesServed = true;
    return true;
}

// Species for edited trees are baked later on the same layout and store, from copies of the
// tree grammars (edits change parameters, never a grammar) and the meshes of the start.
std::unique_ptr<server::SpeciesBakery> speciesBakery(const cells::BatchCatalog& catalog,
                                                     std::unique_ptr<render::TerminalMeshLibrary> library,
                                                     const ServeAssetSetup& setup,
                                                     const lod::SceneImpostorOptions& options) {
    std::vector<std::optional<grammar::CompiledGrammar>> grammars(catalog.index().grammarCount());
    for (uint32_t g = 0; g < grammars.size(); ++g)
        if (catalog.index().isTreeGrammar(g)) grammars[g] = catalog.grammar(g).grammar;
    return std::make_unique<ServeSpeciesBakery>(std::move(grammars), catalog.scene().config.seed,
                                                std::move(library), setup.render.backend, options.treeLayout,
                                                options.storeDirectory);
}

} // namespace

bool impostorAsset(const impostor::ImpostorAtlas& atlas, uint32_t layer,
                   const std::optional<impostor::ImpostorStore>& store, server::ImpostorAsset& asset,
                   std::string& error) {
    asset.key = atlas.contentKey;
    asset.layer = layer;
    asset.centre = array3(atlas.centre);
    asset.radius = atlas.radius;
    asset.boundsMin = array3(atlas.boundsMin);
    asset.boundsMax = array3(atlas.boundsMax);
    std::vector<uint8_t> albedo, normal;
    if (!render::encodePng(atlas.albedo, render::PngTransfer::Srgb, albedo, error) ||
        !render::encodePng(normalDepthImage(atlas.normalDepth), render::PngTransfer::Data, normal, error)) {
        error = atlas.shape + ": " + error;
        return false;
    }
    asset.albedoPng = share(std::move(albedo));
    asset.normalPng = share(std::move(normal));
    if (store) asset.exr = readFile(store->pathFor(atlas.shape, atlas.contentKey));
    return true;
}

nlohmann::json impostorLayoutJson(const impostor::ViewLayout& layout) {
    nlohmann::json views = nlohmann::json::array();
    uint32_t central = 0;
    for (uint32_t v = 0; v < layout.viewCount(); ++v) {
        const glm::vec3 d = layout.direction(v);
        const impostor::ViewBasis basis = impostor::viewBasis(layout.sphere, d);
        const glm::uvec2 tile = layout.tileOrigin(v);
        views.push_back({{"direction", json3(d)},
                         {"right", json3(basis.right)},
                         {"up", json3(basis.up)},
                         {"tile", {tile.x, tile.y}}});
        if (d.z > layout.direction(central).z) central = v;
    }
    return {{"sphere", layout.sphere == impostor::ViewSphere::Hemisphere ? "hemi-octahedral" : "octahedral"},
            {"grid", layout.grid},
            {"view_resolution", layout.viewResolution},
            {"padding", layout.padding},
            {"atlas_size", layout.atlasSize()},
            {"central_view", central},
            {"projection",
             "orthographic over the bounding sphere (centre, radius): a view's tile maps [-radius, radius]^2 "
             "along (right, up) to its inner texels, rows from the top"},
            {"views", views}};
}

ServeAssets buildShapeAssets(const cells::BatchCatalog& catalog, const ServeAssetSetup& setup) {
    ServeAssets out;
    server::ShapeAssets& assets = out.shapes;
    const auto start = std::chrono::steady_clock::now();
    std::unique_ptr<render::TerminalMeshLibrary> library = sceneMeshLibrary(catalog);
    for (const std::string& note : library->notes()) assets.notes.push_back("meshes: " + note);
    addMeshes(catalog, *library, assets);
    if (!setup.render.impostors) {
        assets.notes.push_back("impostors (EXR, PNG): off (--no-impostors)");
        return out;
    }
    bool members = false;
    for (const auto* grammars : {&catalog.scene().buildingGrammars, &catalog.scene().treeGrammars})
        for (const scene::GrammarBuildings& g : *grammars) members |= !g.buildings.empty();
    if (!members) {
        // Without buildings or trees there is nothing to bake, so no GL context is made either.
        assets.notes.push_back("impostors (EXR, PNG): none needed (the scene has no buildings and no trees)");
        return out;
    }
    render::GlContextResult gl = render::createGlContext({setup.render.backend, true});
    if (!gl.context) {
        assets.notes.push_back("impostors (EXR, PNG): not served (no GL context to bake them: " + gl.error() +
                               ")");
        return out;
    }
    assets.notes.push_back(glContextNote(*gl.context) + ", for the impostor bake only");
    lod::SceneImpostorOptions options = sceneImpostorOptions(setup.render);
    lod::SceneImpostors baked;
    lod::SceneImpostorReport report;
    std::string error;
    bool ok = false;
    try {
        ok = lod::bakeSceneImpostors(catalog.scene(), *library, options, baked, report, error) &&
             addImpostors(baked, options.storeDirectory, assets, error);
    } catch (const std::filesystem::filesystem_error& e) {
        error = std::string("impostor store: ") + e.what(); // a folder that cannot be created
    }
    if (!ok) {
        assets.impostors.clear();
        assets.notes.push_back("impostors (EXR, PNG): not served (" + error + ")");
        return out;
    }
    assets.impostorLayout = impostorLayoutJson(options.facadeLayout);
    if (assets.speciesServed) assets.speciesLayout = impostorLayoutJson(options.treeLayout);
    appendImpostorNotes(report, assets.notes);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string trees = assets.speciesServed ? std::to_string(assets.species.size()) + " tree species"
                              : report.treeSpecies ? "tree species not served (a species failed to bake)"
                                                   : "no tree species";
    assets.notes.push_back(
        "impostors (EXR, PNG): facade shapes and " + trees + "; " + std::to_string(assets.byteSize() >> 10) +
        " KiB of meshes and impostor files, built in " + std::to_string(int(seconds * 1000.0)) + " ms");
    if (assets.speciesServed) out.bakery = speciesBakery(catalog, std::move(library), setup, options);
    return out;
}

} // namespace hexlod::apps
