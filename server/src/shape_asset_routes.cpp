// ServiceApi: the shape asset routes (docs/protocol.md): a terminal shape's mesh (and coarse mesh) as .glb,
// its impostor's albedo, normal-depth and EXR files, and the same files of a tree species' impostor. Every
// URL carries its content key, so a reply is immutable and a stale key gets 404 naming the current URL, as
// batch content does.
#include "hexlod/server/service_api.h"

#include "hexlod/cache/batch_key.h"

namespace hexlod::server {
namespace {

struct ShapeTarget {
    uint32_t grammar = 0, shape = 0;
    uint64_t key = 0;
    std::string suffix; // what follows the key's 16 hex digits in the last segment
};

// {grammar}/{shape}/{16 hex digits}{suffix} of a route whose assets are `served`; else the
// reply: 501 when the service serves no `what`, 400 when the target is malformed.
std::optional<ShapeTarget> parseShapeTarget(const RequestContext& c, bool served, const char* what,
                                            Reply& error) {
    const auto grammar = parseUint32(c.params[0]);
    const auto shape = parseUint32(c.params[1]);
    const std::string_view file = c.params[2];
    const auto key = file.size() > 16 ? parseHexDigest(file.substr(0, 16)) : std::nullopt;
    if (!served) {
        error = errorReply(501, std::string(what) +
                                    " are not served by this service (see notes in /api/v1/scene)");
    } else if (!grammar) {
        error = errorReply(400, "grammar must be a grammar index (a whole number), got '" +
                                    std::string(c.params[0]) + "'");
    } else if (!shape) {
        error = errorReply(400, "shape must be a shape index (a whole number), got '" +
                                    std::string(c.params[1]) + "'");
    } else if (!key) {
        error =
            errorReply(400, "expected <16 hex digits of the key><suffix>, got '" + std::string(file) + "'");
    } else {
        return ShapeTarget{*grammar, *shape, *key, std::string(file.substr(16))};
    }
    return std::nullopt;
}

Reply immutableBytes(const Request& request, uint64_t key, const char* contentType, const AssetBytes& bytes) {
    const std::string etag = "\"" + cache::hexDigest(key) + "\"";
    Reply reply;
    reply.set("ETag", etag);
    reply.set("Cache-Control", kImmutable);
    if (const auto inm = request.header("if-none-match"); inm && etagMatches(*inm, etag)) {
        reply.status = 304;
        reply.contentType.clear();
        return reply;
    }
    reply.contentType = contentType;
    reply.payload = bytes;
    return reply;
}

Reply staleKey(const std::string& what, const std::string& current) {
    Reply reply = errorReply(404, "that key is not this " + what + "'s; it is now at " + current);
    reply.set("X-Hexlod-Current", current);
    return reply;
}

// One file of an impostor: `suffix` picks it, a key that is not the impostor's is a 404 naming
// `currentUrl()`.
template <typename CurrentUrl>
Reply impostorFile(const Request& request, const ImpostorAsset& impostor, uint64_t key,
                   const std::string& suffix, const CurrentUrl& currentUrl) {
    const AssetBytes* bytes = suffix == ".albedo.png"   ? &impostor.albedoPng
                              : suffix == ".normal.png" ? &impostor.normalPng
                              : suffix == ".exr"        ? &impostor.exr
                                                        : nullptr;
    if (!bytes)
        return errorReply(404, "an impostor file is <key>.albedo.png, <key>.normal.png or <key>.exr, not '" +
                                   suffix + "'");
    if (impostor.key != key) return staleKey("impostor", currentUrl());
    if (!*bytes) return errorReply(404, "this impostor was baked without a store: it has no EXR");
    return immutableBytes(request, impostor.key, suffix == ".exr" ? "image/x-exr" : "image/png", *bytes);
}

std::string shapeName(const ShapeTarget& t) {
    return "shape " + std::to_string(t.shape) + " of grammar " + std::to_string(t.grammar);
}

} // namespace

void ServiceApi::shapeMesh(const RequestContext& c, Respond respond) const {
    const ShapeAssets& assets = service_.shapeAssets();
    Reply error;
    const auto target = parseShapeTarget(c, assets.meshesServed, "terminal meshes", error);
    if (!target) return respond(std::move(error));
    const bool coarse = target->suffix == ".coarse.glb";
    if (!coarse && target->suffix != ".glb")
        return respond(
            errorReply(404, "a terminal mesh is <key>.glb, or <key>.coarse.glb for its coarse mesh, not '" +
                                target->suffix + "'"));
    const MeshAsset* mesh = assets.mesh(target->grammar, target->shape);
    if (!mesh) return respond(errorReply(404, "the scene declares no " + shapeName(*target)));
    if (!coarse) {
        if (mesh->hash != target->key)
            return respond(staleKey("mesh", service_.meshUrl(target->grammar, target->shape)));
        return respond(immutableBytes(c.request, mesh->hash, "model/gltf-binary", mesh->glb));
    }
    if (!mesh->coarse)
        return respond(errorReply(
            404, shapeName(*target) +
                     " has no coarse mesh (its generator has no coarser level that keeps its look)"));
    if (mesh->coarse->hash != target->key)
        return respond(staleKey("coarse mesh", service_.coarseMeshUrl(target->grammar, target->shape)));
    respond(immutableBytes(c.request, mesh->coarse->hash, "model/gltf-binary", mesh->coarse->glb));
}

void ServiceApi::shapeImpostor(const RequestContext& c, Respond respond) const {
    const ShapeAssets& assets = service_.shapeAssets();
    Reply error;
    const auto target = parseShapeTarget(c, assets.impostorsServed, "impostors", error);
    if (!target) return respond(std::move(error));
    const ImpostorAsset* impostor = assets.impostor(target->grammar, target->shape);
    if (!impostor)
        return respond(errorReply(
            404, shapeName(*target) + " has no impostor (the scene does not use it, or it is not a facade "
                                      "shape)"));
    respond(impostorFile(c.request, *impostor, target->key, target->suffix, [&] {
        return service_.impostorUrl(target->grammar, target->shape, target->suffix.c_str());
    }));
}

void ServiceApi::speciesImpostor(const RequestContext& c, Respond respond) const {
    const ShapeAssets& assets = service_.shapeAssets();
    const auto species = parseUint32(c.params[0]);
    const std::string_view file = c.params[1];
    const auto key = file.size() > 16 ? parseHexDigest(file.substr(0, 16)) : std::nullopt;
    if (!assets.speciesServed)
        return respond(
            errorReply(501, "tree impostors are not served by this service (see notes in /api/v1/scene)"));
    if (!species)
        return respond(errorReply(400, "species must be a species index (a whole number), got '" +
                                           std::string(c.params[0]) + "'"));
    if (!key)
        return respond(
            errorReply(400, "expected <16 hex digits of the key><suffix>, got '" + std::string(file) + "'"));
    const std::optional<SpeciesAsset> asset = service_.species(*species);
    if (!asset)
        return respond(errorReply(404, "the scene has " + std::to_string(service_.speciesCount()) +
                                           " tree species with impostors; there is no species " +
                                           std::to_string(*species)));
    if (asset->retired)
        return respond(errorReply(410, "tree species " + std::to_string(*species) +
                                           " was retired: no tree has its values any more"));
    const std::string suffix(file.substr(16));
    respond(impostorFile(c.request, asset->impostor, *key, suffix,
                         [&] { return service_.speciesImpostorUrl(*species, suffix.c_str()); }));
}

} // namespace hexlod::server
