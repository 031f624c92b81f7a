// strangebeta graph: feature-wise transition graphs and A* interpolation
// (Stuart & Bradley 1998; src/graph, docs/dance.md).
//
//   strangebeta graph train --out G [--influence FILE|learn|none] [--alpha A]
//                           [--reverse-edges] [--min-pair-count N] FILE...
//   strangebeta graph interpolate --graph G --from TOKEN --to TOKEN [--greedy]
//                           [--max-length L] [--memory-mb M] [--max-expanded N]
//                           [--no-influence] [--format text|json]
//   strangebeta graph train --out G --routes FILE.crdl... | --corpus DIR [...]  (climbing)
//   strangebeta graph info --graph G
//   strangebeta graph tokens --routes FILE.crdl... | --corpus DIR [--readable]
//   strangebeta graph evaluate --corpus DIR [...]   (cmd_graph_eval.cc)
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/files.h"
#include "base/number.h"
#include "base/text.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "cli/subcommands.h"
#include "crdl/route.h"
#include "crdl/site_csv.h"
#include "graph/graph.h"
#include "graph/influence.h"
#include "graph/search.h"
#include "graph/tokens.h"
#include "language/symbols.h"
#include "plan/climb_tokens.h"

namespace sb::cli {
namespace {

constexpr const char* kCmd = "graph";

// --memory-mb range (graph::kMinMemoryBytes..kMaxMemoryBytes in MiB).
constexpr int kMaxMemoryMb = static_cast<int>(graph::kMaxMemoryBytes >> 20);

std::string Fmt(double v) { return FormatDouble(v, 17); }

// Climbing tokens (plan/climb_tokens.h) of CRDL route files or of the site
// export's original routes, read with the project's grammar.
Result<std::vector<graph::Sequence>> ClimbInput(const std::vector<std::string>& route_files,
                                                const std::string& corpus) {
  auto lang = language::MoveLanguage::LoadDefault();
  if (!lang.ok()) return lang.status();
  std::vector<Route> routes;
  for (const std::string& f : route_files) {
    auto r = ReadCrdlFile(f);
    if (!r.ok()) return r.status();
    routes.push_back(std::move(r).value());
  }
  if (!corpus.empty()) {
    auto e = ReadSiteExport(corpus);
    if (!e.ok()) return e.status();
    for (const SiteRoute& r : e->routes)
      if (!r.is_variation) routes.push_back(r.route);
  }
  auto seqs = plan::ClimbSequences(routes, *lang);
  if (seqs.empty()) return Status::InvalidInput("no move of these routes is readable");
  return seqs;
}

int Train(const std::vector<std::string>& files, const std::vector<std::string>& route_files,
          const std::string& corpus, const std::string& out, const std::string& influence,
          double alpha, bool reverse, uint32_t min_pair) {
  std::vector<graph::Sequence> seqs;
  int k = 0;
  size_t tokens = 0;
  const bool climbing = !route_files.empty() || !corpus.empty();
  if (climbing) {
    if (!files.empty()) {
      return Fail(kCmd, Status::InvalidInput("give token FILEs or --routes/--corpus, not both"));
    }
    auto c = ClimbInput(route_files, corpus);
    if (!c.ok()) return Fail(kCmd, c.status());
    seqs = std::move(c).value();
    k = plan::kClimbFeatures;
    for (const auto& s : seqs) tokens += s.size();
  }
  for (const std::string& f : files) {
    auto data = ReadFile(f);
    if (!data.ok()) return Fail(kCmd, data.status());
    auto tf = graph::ParseTokenFile(*data, f, k);
    if (!tf.ok()) return Fail(kCmd, tf.status());
    if (tf->tokens == 0) continue;
    k = tf->k;
    tokens += tf->tokens;
    if (tokens > graph::kMaxTokens) {
      return Fail(kCmd, Status::InvalidInput(f + ": more than " +
                                             std::to_string(graph::kMaxTokens) + " tokens"));
    }
    for (auto& s : tf->sequences) seqs.push_back(std::move(s));
  }
  if (tokens == 0) return Fail(kCmd, Status::InvalidInput("no tokens in the training files"));
  graph::TrainOptions o;
  o.alpha = alpha;
  o.reverse_edges = reverse;
  o.min_pair_count = min_pair;
  if (influence == "learn") {
    o.influence = graph::InfluenceMode::kLearned;
  } else if (influence != "none") {
    auto data = ReadFile(influence);
    if (!data.ok()) return Fail(kCmd, data.status());
    auto pairs = graph::ParseInfluenceFile(*data, influence, k);
    if (!pairs.ok()) return Fail(kCmd, pairs.status());
    o.influence = graph::InfluenceMode::kGiven;
    o.pairs = std::move(pairs).value();
  }
  auto g = graph::GraphModel::Train(seqs, k, o);
  if (!g.ok())
    return Fail(kCmd, Status::InvalidInput("--out " + out + ": " + g.status().message()));
  if (climbing) {
    Status st = g->set_metadata({{"grammar", "climbing"}, {"tokens", "climbing"}});
    if (!st.ok()) return Fail(kCmd, st);
  }
  if (Status s = graph::SaveGraph(*g, out); !s.ok()) return Fail(kCmd, s);
  std::fprintf(
      stderr,
      "trained %d feature graphs on %zu tokens in %zu sequences, influence %s (%zu pairs) -> %s\n",
      k, tokens, seqs.size(), graph::InfluenceModeName(g->options().influence),
      g->influence().size(), out.c_str());
  return 0;
}

Result<std::vector<int32_t>> ParseState(const graph::GraphModel& g, const std::string& text,
                                        const char* opt) {
  auto t = graph::ParseToken(text, g.num_features(), opt);
  if (!t.ok()) return t.status();
  return g.Encode(*t, opt);
}

int Interpolate(const std::string& path, const std::string& from, const std::string& to,
                const graph::SearchOptions& so, const std::string& format) {
  auto g = graph::LoadGraph(path);
  if (!g.ok()) return Fail(kCmd, g.status());
  auto a = ParseState(*g, from, "--from");
  if (!a.ok()) return Fail(kCmd, a.status());
  auto b = ParseState(*g, to, "--to");
  if (!b.ok()) return Fail(kCmd, b.status());
  auto r = graph::Interpolate(*g, *a, *b, so);
  if (!r.ok()) return Fail(kCmd, r.status());
  const bool found = r->outcome == graph::Outcome::kFound;
  std::string out;
  if (format == "json") {
    nlohmann::json j;
    j["found"] = found;
    j["strategy"] = so.strategy == graph::Strategy::kGreedy ? "greedy" : "astar";
    nlohmann::json ins = nlohmann::json::array();
    for (const auto& s : r->inserted) ins.push_back(graph::FormatToken(g->Decode(s)));
    j["inserted"] = ins;
    if (found) {
      j["cost"] = r->cost;
    } else {
      j["cost"] = nullptr;
      j["reason"] = r->reason;
    }
    j["expanded"] = r->stats.expanded;
    j["generated"] = r->stats.generated;
    j["candidates"] = r->stats.candidates;
    j["peak_bytes"] = r->stats.peak_bytes;
    j["depth_first"] = r->stats.depth_first;
    j["iterations"] = r->stats.iterations;
    out = j.dump() + "\n";
  } else {
    out = "from  " + from + "\n";
    for (size_t i = 0; i < r->inserted.size(); ++i) {
      out += std::to_string(i + 1) + "     " + graph::FormatToken(g->Decode(r->inserted[i])) + "\n";
    }
    out += "to    " + to + "\n";
    if (found) {
      out += "cost: " + Fmt(r->cost) + " nats over " + std::to_string(r->inserted.size() + 1) +
             " transitions (" + std::to_string(r->inserted.size()) + " inserted)\n";
    } else {
      out += "no interpolation: " + r->reason + "\n";
    }
    out += "expanded " + std::to_string(r->stats.expanded) + ", generated " +
           std::to_string(r->stats.generated) + ", peak memory " +
           std::to_string(r->stats.peak_bytes) + " bytes" +
           (r->stats.depth_first ? ", depth first after the memory bound (" +
                                       std::to_string(r->stats.iterations) + " iterations)"
                                 : std::string()) +
           "\n";
  }
  if (int rc = WriteOutput(kCmd, "-", out); rc != 0) return rc;
  return found ? 0 : 1;
}

int Info(const std::string& path) {
  auto g = graph::LoadGraph(path);
  if (!g.ok()) return Fail(kCmd, g.status());
  std::string out = "features " + std::to_string(g->num_features()) + "\n";
  for (int f = 0; f < g->num_features(); ++f) {
    size_t edges = 0;
    for (size_t q = 0; q < g->values(f).size(); ++q) {
      edges += g->OutEdges(f, static_cast<int32_t>(q)).size();
    }
    out += "feature " + std::to_string(f + 1) + ": " + std::to_string(g->values(f).size()) +
           " values, " + std::to_string(edges) + " edges\n";
  }
  out += "smoothing alpha " + Fmt(g->options().alpha) + ", reverse edges " +
         (g->options().reverse_edges ? "on" : "off") + ", min pair count " +
         std::to_string(g->options().min_pair_count) + "\n";
  out += "influence " + std::string(graph::InfluenceModeName(g->options().influence)) + ":";
  for (const auto& p : g->influence()) {
    out += " " + std::to_string(p.child + 1) + "<-" + std::to_string(p.parent + 1);
  }
  out += "\n";
  return WriteOutput(kCmd, "-", out);
}

int RunTrain(const std::vector<std::string>& args) {
  CLI::App app{
      "Train one transition graph per feature on token files (one sequence a line, "
      "tokens v1|v2|...|vk with the same k throughout) and write the graph file.",
      "strangebeta graph train"};
  std::vector<std::string> files, route_files;
  std::string out, influence = "none", corpus;
  double alpha = 0;
  bool reverse = false;
  uint32_t min_pair = 1;
  app.add_option("files", files, "token files");
  app.add_option("--routes", route_files,
                 "train on the moves of CRDL route files as climbing tokens (9 features, "
                 "docs/dance.md), read with the project's grammar");
  app.add_option("--corpus", corpus,
                 "train on the original (non-variation) routes of the site's CSV export in DIR "
                 "as climbing tokens");
  app.add_option("--out", out, "graph file to write")->required();
  app.add_option("--influence", influence,
                 "influence diagram: a file of 'child parent' lines (1-based feature "
                 "positions), 'learn' (Chow-Liu tree of mutual information) or 'none'")
      ->capture_default_str();
  app.add_option("--alpha", alpha,
                 "additive smoothing: w = ln(C(q)+alpha*M) - ln(C(q,r)+alpha) over every "
                 "value pair (0 = the paper's estimate: only observed edges; at most 1e6)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, graph::kMaxAlpha));
  app.add_flag("--reverse-edges", reverse,
               "count every observed transition q->r also as r->q (the paper's proposal for "
               "moving 'upstream')");
  app.add_option("--min-pair-count", min_pair,
                 "a state is admissible when each influence pair's values occur together in "
                 "at least this many training tokens (1..1e9)")
      ->capture_default_str()
      ->check(CLI::Range(1u, 1000000000u));
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  if (files.empty() && route_files.empty() && corpus.empty()) {
    return Fail(kCmd, Status::InvalidInput("give token FILEs, --routes or --corpus"));
  }
  return Train(files, route_files, corpus, out, influence, alpha, reverse, min_pair);
}

int RunInterpolate(const std::vector<std::string>& args) {
  CLI::App app{
      "The cheapest sequence of states between --from and --to (A*: cost g = summed "
      "edge weights, heuristic h = summed per-feature shortest paths), or greedy "
      "(f = h). Prints the inserted states, the cost in nats of every transition from "
      "--from to --to, and the search statistics. Exit 1 when there is none.",
      "strangebeta graph interpolate"};
  std::string gpath, from, to, format = "text";
  bool greedy = false, no_influence = false;
  graph::SearchOptions so;
  int memory_mb = static_cast<int>(so.memory_bytes >> 20);
  app.add_option("--graph", gpath, "graph file (graph train)")->required();
  app.add_option("--from", from, "start state v1|...|vk")->required();
  app.add_option("--to", to, "goal state v1|...|vk")->required();
  app.add_flag("--greedy", greedy, "score f = h (the paper's greedy variant) instead of g + h");
  app.add_option("--max-length", so.max_length,
                 "at most this many inserted states (0.." + std::to_string(graph::kMaxLength) + ")")
      ->capture_default_str()
      ->check(CLI::Range(0, graph::kMaxLength));
  app.add_option("--memory-mb", memory_mb,
                 "memory bound of the search in MiB (1.." + std::to_string(kMaxMemoryMb) +
                     "); past it the search goes on depth first (IDA*)")
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxMemoryMb));
  app.add_option("--max-expanded", so.max_expanded,
                 "give up after expanding this many states (1..1e10)")
      ->capture_default_str()
      ->check(CLI::Range(uint64_t{1}, graph::kMaxExpandedLimit));
  app.add_flag("--no-influence", no_influence,
               "ignore the influence diagram: every combination of values is admissible");
  app.add_option("--format", format, "text or json")
      ->capture_default_str()
      ->check(CLI::IsMember({"text", "json"}));
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  so.strategy = greedy ? graph::Strategy::kGreedy : graph::Strategy::kAStar;
  so.use_influence = !no_influence;
  so.memory_bytes = static_cast<size_t>(memory_mb) << 20;
  return Interpolate(gpath, from, to, so, format);
}

int RunTokens(const std::vector<std::string>& args) {
  CLI::App app{
      "Print the climbing tokens (v1|...|v9: hand, verb, move-size, hold, hold-size, "
      "hold-shape, cross, big, good) of routes, one route a line; with --readable, "
      "each token written back as a move.",
      "strangebeta graph tokens"};
  std::vector<std::string> route_files;
  std::string corpus;
  bool readable = false;
  app.add_option("--routes", route_files, "CRDL route files");
  app.add_option("--corpus", corpus, "the site's CSV export directory (original routes)");
  app.add_flag("--readable", readable, "one readable move a line instead of tokens");
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  if (route_files.empty() && corpus.empty()) {
    return Fail(kCmd, Status::InvalidInput("give --routes or --corpus"));
  }
  auto seqs = ClimbInput(route_files, corpus);
  if (!seqs.ok()) return Fail(kCmd, seqs.status());
  auto lang = language::MoveLanguage::LoadDefault();
  if (!lang.ok()) return Fail(kCmd, lang.status());
  std::string out;
  for (const auto& s : *seqs) {
    for (size_t i = 0; i < s.size(); ++i) {
      if (readable) {
        out += plan::ReadableClimbMove(s[i], *lang) + "\n";
      } else {
        out += (i ? " " : "") + graph::FormatToken(s[i]);
      }
    }
    out += "\n";
  }
  return WriteOutput(kCmd, "-", out);
}

int RunInfo(const std::vector<std::string>& args) {
  CLI::App app{"Print a graph file's features, values, edges and influence pairs.",
               "strangebeta graph info"};
  std::string path;
  app.add_option("--graph", path, "graph file")->required();
  if (int rc = ParseArgs(app, args); rc >= 0) return rc;
  return Info(path);
}

}  // namespace

// graph evaluate lives in cmd_graph_eval.cc.
int RunGraphEvaluate(const std::vector<std::string>& args);

int RunGraph(const std::vector<std::string>& args) {
  static const Subcommand kTable[] = {
      {"train", "train per-feature transition graphs on token files", RunTrain},
      {"interpolate", "A* (or greedy) interpolation between two states", RunInterpolate},
      {"info", "summarise a graph file", RunInfo},
      {"tokens", "climbing routes as tokens (or readable moves)", RunTokens},
      {"evaluate", "corpus evaluation of A*, greedy and VOMM smoothing of climbing variations",
       RunGraphEvaluate},
  };
  return RunSubcommands(
      kCmd,
      "Feature-wise transition graphs and A* interpolation (Stuart & Bradley 1998, the dance\n"
      "method): a state is a vector of feature values written v1|v2|...|vk. See docs/dance.md.",
      kTable, args);
}

}  // namespace sb::cli
