#include "serve_species_bakery.h"

#include "serve_shape_assets.h"

namespace hexlod::apps {

ServeSpeciesBakery::ServeSpeciesBakery(std::vector<std::optional<grammar::CompiledGrammar>> treeGrammars,
                                       uint64_t seed, std::unique_ptr<render::TerminalMeshLibrary> meshes,
                                       render::GlBackend backend, impostor::ViewLayout treeLayout,
                                       const std::string& storeDirectory)
    : grammars_(std::move(treeGrammars)), seed_(seed), meshes_(std::move(meshes)), backend_(backend),
      treeLayout_(std::move(treeLayout)),
      store_(storeDirectory.empty() ? std::nullopt : std::optional<impostor::ImpostorStore>(storeDirectory)),
      thread_([this] { run(); }) {}

ServeSpeciesBakery::~ServeSpeciesBakery() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

void ServeSpeciesBakery::bake(server::SpeciesRequest request, Done done) {
    {
        std::lock_guard lock(mutex_);
        queue_.emplace_back(std::move(request), std::move(done));
    }
    wake_.notify_one();
}

void ServeSpeciesBakery::run() {
    // The context is made at once, on the thread that uses it: making it and building the
    // bake shaders takes seconds on a software GL, which the first tree edit should not wait.
    std::unique_ptr<render::GlContext> gl;
    impostor::ImpostorBaker baker;
    std::string setupError;
    render::GlContextResult made = render::createGlContext({backend_, true});
    if (!made.context)
        setupError = "no GL context to bake it: " + made.error();
    else if (!baker.init(setupError))
        setupError = "the baker does not build: " + setupError;
    else
        gl = std::move(made.context);
    for (;;) {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (stopping_) return;
        auto [request, done] = std::move(queue_.front());
        queue_.pop_front();
        lock.unlock();
        if (request.stillWanted && !request.stillWanted()) continue;
        std::string error = setupError;
        std::optional<server::SpeciesAsset> asset;
        try {
            if (gl) asset = bakeOne(baker, request, error);
        } catch (const std::exception& e) {
            error = e.what(); // the store's folder cannot be made, say: this bake fails, the thread goes on
        }
        done(std::move(asset), error);
    }
}

std::optional<server::SpeciesAsset> ServeSpeciesBakery::bakeOne(impostor::ImpostorBaker& baker,
                                                                const server::SpeciesRequest& request,
                                                                std::string& error) {
    if (request.grammar >= grammars_.size() || !grammars_[request.grammar]) {
        error = "grammar " + std::to_string(request.grammar) + " is not a tree grammar";
        return std::nullopt;
    }
    lod::TreeSpeciesBake species;
    species.grammar = &*grammars_[request.grammar];
    species.grammarIndex = request.grammar;
    species.parameters = request.parameters;
    species.seed = seed_;
    species.name = "tree:" + request.name;
    impostor::ImpostorAtlas atlas;
    lod::BakedShapeReport report;
    const impostor::ImpostorStore* const store = store_ ? &*store_ : nullptr;
    if (!lod::bakeTreeSpecies(baker, store, species, *meshes_, treeLayout_, atlas, report)) {
        error = report.note;
        return std::nullopt;
    }
    server::SpeciesAsset asset;
    asset.name = request.name;
    asset.grammar = request.grammar;
    asset.parameters = request.parameters;
    if (!impostorAsset(atlas, 0, store_, asset.impostor, error)) return std::nullopt;
    return asset;
}

} // namespace hexlod::apps
