// Client-side measurements of a running `hexlod serve` (docs/BENCHMARKS.md, "Service"):
//   serve_bench edits --port P [--building ID] [--grammar NAME] [--repeat N]
//     edit latency: POST, then the SSE event, then the new payload available; median and p95,
//     for one building and for a whole grammar across the resident cells.
//   serve_bench sizes --port P
//     bytes per cell on the wire (encoded payloads) against in memory (decoded sets).
//   serve_bench species --port P [--repeat N] [--burst B]
//     tree edit to billboards: a cell's trees get a parameter value not used before, and the
//     service bakes a species per value set they then have; POST to the first and to the last
//     species event, and to the first species' albedo PNG fetched. With a burst, B edits are
//     posted back to back (a slider released again and again) and the times run from the
//     last; species_per_edit counts every species announced for the burst.
// Prints one JSON object. Timing is wall time on the client, loopback only.
#include "hexlod/grammar/extruded_set_codec.h"
#include "hexlod/grammar/terminal_set_codec.h"
#include "hexlod/http_client/http_client.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;
using namespace hexlod;

struct Options {
    std::string mode;
    uint16_t port = 8080;
    uint32_t building = 0;
    std::string grammar = "residential";
    int repeat = 30;
    int connections = 4;
    int burst = 1; // species: edits posted back to back, timed from the last
};

double ms(Clock::duration d) {
    return std::chrono::duration<double, std::milli>(d).count();
}

Json summary(std::vector<double> values) {
    if (values.empty()) return nullptr;
    std::sort(values.begin(), values.end());
    const auto at = [&](double q) {
        return values[static_cast<size_t>(q * double(values.size() - 1) + 0.5)];
    };
    return {{"median_ms", at(0.5)},
            {"p95_ms", at(0.95)},
            {"min_ms", values.front()},
            {"max_ms", values.back()},
            {"runs", values.size()}};
}

Json getJson(http_client::Connection& c, const std::string& target) {
    const auto r = c.get(target);
    if (r.status != 200) throw std::runtime_error(target + ": status " + std::to_string(r.status));
    return Json::parse(r.body);
}

// Fetches every URL, spread over `connections` connections; throws on a non-200.
void fetchAll(uint16_t port, const std::vector<std::string>& urls, int connections) {
    std::vector<std::thread> threads;
    std::vector<std::string> errors(connections);
    for (int t = 0; t < connections; ++t)
        threads.emplace_back([&, t] {
            http_client::Connection c("127.0.0.1", port);
            for (size_t i = t; i < urls.size(); i += connections) {
                const auto r = c.get(urls[i]);
                if (r.status != 200) errors[t] = urls[i] + ": " + std::to_string(r.status);
            }
        });
    for (std::thread& t : threads) t.join();
    for (const std::string& e : errors)
        if (!e.empty()) throw std::runtime_error(e);
}

Json measureEdits(const Options& o, const std::string& selector, bool wholeGrammar) {
    http_client::Connection c("127.0.0.1", o.port);
    const Json scene = getJson(c, "/api/v1/scene");
    int grammarIndex = -1;
    for (const Json& g : scene["grammars"])
        if (g["name"] == o.grammar) grammarIndex = g["index"];
    if (grammarIndex < 0) throw std::runtime_error("no grammar " + o.grammar);
    if (wholeGrammar) { // make every batch of the grammar resident first
        std::vector<std::string> urls;
        const Json index = getJson(c, "/api/v1/cells");
        for (const Json& cell : index["cells"])
            for (const Json& batch : cell["batches"])
                if (batch["grammar"] == grammarIndex) urls.push_back(batch["terminal_set"]);
        fetchAll(o.port, urls, o.connections);
    }
    http_client::EventStreamReader events("127.0.0.1", o.port, "/api/v1/events");
    if (!events.next(std::chrono::seconds(5))) throw std::runtime_error("no hello event");
    std::vector<double> acknowledged, notified, available;
    size_t batches = 0;
    for (int i = 0; i < o.repeat; ++i) {
        // A value not used before, so that every edit changes keys and misses every cache.
        const double floorHeight = 3.1 + 0.002 * (i + 1) + (wholeGrammar ? 0.5 : 0.0);
        const std::string body = "{\"selector\":" + selector +
                                 ",\"params\":{\"floor_h\":" + std::to_string(floorHeight) +
                                 "},\"comment\":\"serve_bench\"}";
        const auto start = Clock::now();
        const auto reply = c.post("/api/v1/edits", body);
        const auto acked = Clock::now();
        if (reply.status != 200) throw std::runtime_error("edit: " + reply.body);
        const uint64_t seq = Json::parse(reply.body)["seq"];
        Json event;
        while (true) {
            const auto e = events.next(std::chrono::seconds(10));
            if (!e) throw std::runtime_error("no event for edit " + std::to_string(seq));
            if (e->id == std::to_string(seq)) {
                event = Json::parse(e->data);
                break;
            }
        }
        const auto seen = Clock::now();
        std::vector<std::string> urls;
        for (const Json& change : event["changed"]) urls.push_back(change["terminal_set"]);
        batches = urls.size();
        fetchAll(o.port, urls, wholeGrammar ? o.connections : 1);
        const auto ready = Clock::now();
        acknowledged.push_back(ms(acked - start));
        notified.push_back(ms(seen - start));
        available.push_back(ms(ready - start));
    }
    return {{"selector", Json::parse(selector)},
            {"changed_batches", batches},
            {"post_to_reply", summary(acknowledged)},
            {"post_to_event", summary(notified)},
            {"post_to_payload", summary(available)}};
}

Json measureSizes(const Options& o) {
    http_client::Connection c("127.0.0.1", o.port);
    std::vector<double> wire, memory;
    uint64_t wireTotal = 0, memoryTotal = 0, terminals = 0;
    struct PerGrammar {
        uint64_t terminals = 0, terminalWire = 0, terminalMemory = 0, extrudedWire = 0, extrudedMemory = 0;
    };
    std::map<int, PerGrammar> perGrammar;
    const Json index = getJson(c, "/api/v1/cells");
    for (const Json& cell : index["cells"]) {
        uint64_t cellWire = 0, cellMemory = 0;
        for (const Json& batch : cell["batches"]) {
            const auto t = c.get(batch["terminal_set"]);
            const auto e = c.get(batch["extruded_set"]);
            if (t.status != 200 || e.status != 200) throw std::runtime_error("content fetch failed");
            grammar::TerminalSet set;
            grammar::ExtrudedSetHeader header;
            grammar::ExtrudedSet extruded;
            std::string error;
            const auto bytes = [](const std::string& s) {
                return std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(s.data()), s.size());
            };
            if (!grammar::decodeTerminalSet(bytes(t.body), set, error) ||
                !grammar::decodeExtrudedSet(bytes(e.body), header, extruded, error))
                throw std::runtime_error("decode: " + error);
            PerGrammar& g = perGrammar[batch["grammar"].get<int>()];
            g.terminals += set.records.size();
            g.terminalWire += t.body.size();
            g.terminalMemory += set.byteSize();
            g.extrudedWire += e.body.size();
            g.extrudedMemory += extruded.byteSize();
            cellWire += t.body.size() + e.body.size();
            cellMemory += set.byteSize() + extruded.byteSize();
            terminals += set.records.size();
        }
        wire.push_back(double(cellWire));
        memory.push_back(double(cellMemory));
        wireTotal += cellWire;
        memoryTotal += cellMemory;
    }
    const auto stats = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        double sum = 0;
        for (double x : v) sum += x;
        return Json{{"median", v[v.size() / 2]}, {"mean", sum / double(v.size())}, {"max", v.back()}};
    };
    Json grammars = Json::object();
    for (const auto& [index, g] : perGrammar)
        grammars[std::to_string(index)] = {
            {"terminals", g.terminals},
            {"terminal_set_wire_bytes", g.terminalWire},
            {"terminal_set_memory_bytes", g.terminalMemory},
            {"wire_bytes_per_terminal", g.terminals ? double(g.terminalWire) / double(g.terminals) : 0.0},
            {"extruded_set_wire_bytes", g.extrudedWire},
            {"extruded_set_memory_bytes", g.extrudedMemory}};
    return {{"cells", wire.size()},
            {"per_grammar", grammars},
            {"terminals", terminals},
            {"wire_bytes_per_cell", stats(wire)},
            {"memory_bytes_per_cell", stats(memory)},
            {"wire_bytes_total", wireTotal},
            {"memory_bytes_total", memoryTotal},
            {"memory_to_wire", double(memoryTotal) / double(wireTotal)}};
}

// The value of one sample line of /metrics ("name{labels} value"), or -1 when it is missing.
double metricValue(http_client::Connection& c, const std::string& sample) {
    // At a line's start: a family's # HELP line names it too.
    const std::string text = "\n" + c.get("/metrics").body;
    const size_t at = text.find("\n" + sample + " ");
    return at == std::string::npos ? -1.0 : std::stod(text.substr(at + sample.size() + 2));
}

Json measureSpecies(const Options& o) {
    http_client::Connection c("127.0.0.1", o.port);
    const Json scene = getJson(c, "/api/v1/scene");
    if (!scene["capabilities"]["tree_billboards"].get<bool>())
        throw std::runtime_error("no tree billboards served");
    const Json* trees = nullptr;
    for (const Json& g : scene["grammars"])
        if (g["kind"] == "tree" && !trees) trees = &g;
    if (!trees) throw std::runtime_error("the scene has no tree grammar");
    const Json& parameter = (*trees)["parameters"][0];
    Json cell;
    const Json index = getJson(c, "/api/v1/cells");
    for (const Json& entry : index["cells"])
        for (const Json& batch : entry["batches"])
            if (batch["grammar"] == (*trees)["index"] && cell.is_null()) cell = {entry["q"], entry["r"]};
    http_client::EventStreamReader events("127.0.0.1", o.port, "/api/v1/events");
    if (!events.next(std::chrono::seconds(5))) throw std::runtime_error("no hello event");
    std::vector<double> first, last, fetched, perEdit;
    const double lo = parameter["min"], hi = parameter["max"];
    for (int i = 0; i < o.repeat; ++i) {
        Clock::time_point start;
        for (int b = 0; b < o.burst; ++b) {
            // A value not used before, inside the declared range: from the journal's next seq,
            // so that a second run on the same service does not repeat the first's.
            const double next = double(getJson(c, "/healthz")["seq"].get<uint64_t>() + 1);
            const double value = lo + (hi - lo) * (0.3 + 0.4 * std::fmod(next * 0.6180339887, 1.0));
            const std::string body = "{\"selector\":{\"cell\":" + cell.dump() + "},\"params\":{\"" +
                                     parameter["name"].get<std::string>() + "\":" + std::to_string(value) +
                                     "}}";
            start = Clock::now();
            if (c.post("/api/v1/edits", body).status != 200)
                throw std::runtime_error("edit refused: " + body);
        }
        size_t species = 0;
        while (true) {
            const auto e = events.next(std::chrono::seconds(60));
            if (!e) throw std::runtime_error("no species event within 60 s");
            if (e->event == "species-failed") throw std::runtime_error("species bake failed: " + e->data);
            if (e->event != "species") continue;
            const auto now = Clock::now();
            if (species++ == 0) {
                first.push_back(ms(now - start));
                const auto png = c.get(Json::parse(e->data)["species"]["impostor"]["albedo_url"]);
                if (png.status != 200)
                    throw std::runtime_error("species albedo: " + std::to_string(png.status));
                fetched.push_back(ms(Clock::now() - start));
            }
            if (metricValue(c, "hexlod_tree_species{state=\"baking\"}") == 0.0) {
                last.push_back(ms(now - start));
                break;
            }
        }
        perEdit.push_back(double(species));
    }
    std::sort(perEdit.begin(), perEdit.end());
    return {{"cell", cell},
            {"parameter", parameter["name"]},
            {"median_species_per_edit", perEdit[perEdit.size() / 2]},
            {"post_to_first_species", summary(first)},
            {"post_to_first_species_png", summary(fetched)},
            {"post_to_last_species", summary(last)},
            // -1 from a service that does not count them
            {"species_dropped_total", metricValue(c, "hexlod_tree_species_dropped_total")},
            {"species_retired_total", metricValue(c, "hexlod_tree_species_retired_total")}};
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    if (argc < 2) {
        std::cerr << "usage: serve_bench edits|sizes|species --port P [--building ID] [--grammar NAME] "
                     "[--repeat N] [--burst B]\n";
        return 2;
    }
    o.mode = argv[1];
    for (int i = 2; i + 1 < argc; i += 2) {
        const std::string flag = argv[i], value = argv[i + 1];
        if (flag == "--port")
            o.port = static_cast<uint16_t>(std::stoi(value));
        else if (flag == "--building")
            o.building = static_cast<uint32_t>(std::stoul(value));
        else if (flag == "--grammar")
            o.grammar = value;
        else if (flag == "--repeat")
            o.repeat = std::stoi(value);
        else if (flag == "--connections")
            o.connections = std::stoi(value);
        else if (flag == "--burst")
            o.burst = std::max(1, std::stoi(value));
        else {
            std::cerr << "serve_bench: unknown option " << flag << "\n";
            return 2;
        }
    }
    try {
        Json out;
        if (o.mode == "edits") {
            // One building of each building grammar (their batches differ a lot in size), then a
            // whole grammar.
            http_client::Connection c("127.0.0.1", o.port);
            std::map<std::string, uint32_t> firstOf;
            const size_t buildings = getJson(c, "/api/v1/scene")["counts"]["buildings"];
            for (uint32_t id = o.building; id < buildings && firstOf.size() < 2; id += 97)
                firstOf.emplace(getJson(c, "/api/v1/buildings/" + std::to_string(id))["grammar_name"], id);
            for (const auto& [grammarName, id] : firstOf)
                out["single_building"][grammarName] =
                    measureEdits(o, "{\"buildings\":[" + std::to_string(id) + "]}", false);
            out["whole_grammar"] = measureEdits(o, "{\"grammar\":\"" + o.grammar + "\"}", true);
        } else if (o.mode == "sizes") {
            out = measureSizes(o);
        } else if (o.mode == "species") {
            out = measureSpecies(o);
        } else {
            std::cerr << "serve_bench: unknown mode " << o.mode << "\n";
            return 2;
        }
        std::cout << out.dump(2) << "\n";
    } catch (const std::exception& e) {
        std::cerr << "serve_bench: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
