// Baking a tree species' impostor while the service runs. An edit can give trees parameter
// values that no species baked at start has, and a client draws such trees from their
// terminals at any distance; so the service asks a bakery for each new set of values and
// serves the atlas once it is done. The app implements the bakery
// (apps/serve_species_bakery.h) with GL, which this module does not link.
#pragma once

#include "hexlod/server/shape_assets.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace hexlod::server {

struct SpeciesRequest {
    uint32_t grammar = 0; // a tree grammar, scene order
    std::vector<float> parameters;
    std::string name;
    // Asked on the bakery's thread just before the bake: false drops the request without
    // calling its `done` (edits since gave its trees other values, as a slider released again
    // and again does; baking every value in between would keep the last one waiting). Empty:
    // always baked.
    std::function<bool()> stillWanted;
};

class SpeciesBakery {
public:
    // The asset (its impostor's layer not yet set), or nullopt and why the bake failed.
    using Done = std::function<void(std::optional<SpeciesAsset> asset, const std::string& error)>;

    virtual ~SpeciesBakery() = default;
    // Queues the bake and returns at once; `done` runs later, on the bakery's own thread. A
    // bakery destroyed first drops what is still queued without calling `done`.
    virtual void bake(SpeciesRequest request, Done done) = 0;
};

} // namespace hexlod::server
