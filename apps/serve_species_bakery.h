// The bakery `hexlod serve` gives its service (server/species_bakery.h): one thread with its
// own GL context, made when it starts, that bakes a species' impostor on the same tree
// layout and store as the start's bake, one request after another (dropping one whose values
// no tree has by its turn, SpeciesRequest::stillWanted), and hands back its served files.
// Without a GL context every request fails with the reason, and the trees stay terminals.
#pragma once

#include "city_session.h"

#include "hexlod/impostor/impostor_baker.h"
#include "hexlod/server/species_bakery.h"

#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

namespace hexlod::apps {

class ServeSpeciesBakery final : public server::SpeciesBakery {
public:
    // `treeGrammars`: every grammar of the scene in its order, only tree grammars filled.
    ServeSpeciesBakery(std::vector<std::optional<grammar::CompiledGrammar>> treeGrammars, uint64_t seed,
                       std::unique_ptr<render::TerminalMeshLibrary> meshes, render::GlBackend backend,
                       impostor::ViewLayout treeLayout, const std::string& storeDirectory);
    ~ServeSpeciesBakery() override; // drops what is queued, finishes the bake under way
    void bake(server::SpeciesRequest request, Done done) override;

private:
    void run();
    std::optional<server::SpeciesAsset> bakeOne(impostor::ImpostorBaker& baker,
                                                const server::SpeciesRequest& request, std::string& error);

    const std::vector<std::optional<grammar::CompiledGrammar>> grammars_;
    const uint64_t seed_;
    const std::unique_ptr<render::TerminalMeshLibrary> meshes_;
    const render::GlBackend backend_;
    const impostor::ViewLayout treeLayout_;
    const std::optional<impostor::ImpostorStore> store_; // none: bake in memory only

    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::pair<server::SpeciesRequest, Done>> queue_;
    bool stopping_ = false;
    std::thread thread_; // last: started once everything above is
};

} // namespace hexlod::apps
