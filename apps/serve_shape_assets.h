// What `hexlod serve` builds before it answers: every declared shape's mesh as .glb, and the
// impostors of the facade shapes the scene's buildings emit and of the tree species its trees
// use, baked (or loaded from the EXR store) in a GL context that lives only for the bake. Without a GL
// context, or with impostors off, the service serves meshes only and says why in its notes.
#pragma once

#include "city_session.h"

#include "hexlod/server/shape_assets.h"
#include "hexlod/server/species_bakery.h"

namespace hexlod::apps {

struct ServeAssetSetup {
    RenderSetup render; // GL backend, facade layout, store; render.impostors false: meshes only
};

struct ServeAssets {
    server::ShapeAssets shapes;
    // Bakes the species that edits make (serve_species_bakery.h); null unless species are served.
    std::unique_ptr<server::SpeciesBakery> bakery;
};

ServeAssets buildShapeAssets(const cells::BatchCatalog& catalog, const ServeAssetSetup& setup);

// One baked atlas as served files: PNGs encoded here, the EXR read back from the store. False
// with a reason when a PNG cannot be encoded.
bool impostorAsset(const impostor::ImpostorAtlas& atlas, uint32_t layer,
                   const std::optional<impostor::ImpostorStore>& store, server::ImpostorAsset& asset,
                   std::string& error);

// The JSON of a facade layout for clients (docs/protocol.md, "impostor_layout"): the grid, the
// tile geometry, and each view's direction and image axes, so a client needs no copy of the
// octahedral mapping to pick and blend views.
nlohmann::json impostorLayoutJson(const impostor::ViewLayout& layout);

} // namespace hexlod::apps
