#include "plan/smoothing_eval.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <utility>

#include "chaos/variation.h"
#include "markov/interpolate.h"
#include "markov/token_model.h"
#include "plan/climb_tokens.h"

namespace sb::plan {
namespace {

constexpr int kSymbolSet = 2;  // k3: hold types + quality flags (the bundled model's set)

bool Continues(const chaos::VariedMove& a, const chaos::VariedMove& b) {
  return a.source && b.source && a.source->route == b.source->route &&
         a.source->move + 1 == b.source->move;
}

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// -log2 P(seq | ctx) under the judge, per transition.
double JudgeBits(const markov::TokenModel& judge, const std::vector<std::string>& ctx,
                 const std::vector<std::string>& seq) {
  auto c = judge.Encode(ctx);
  auto s = judge.Encode(seq);
  return judge.model().LogLoss(*s, *c) / static_cast<double>(seq.size());
}

std::string Fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v + 0.0);
  return buf;
}

}  // namespace

Result<EvalReport> EvaluateSmoothing(const std::vector<Route>& routes, language::MoveLanguage& lang,
                                     const EvalOptions& o) {
  if (o.variations < 1 || o.variations > kMaxEvalVariations) {
    return Status::InvalidInput("variations must be in 1.." + std::to_string(kMaxEvalVariations));
  }
  if (o.max_length < 0 || o.max_length > graph::kMaxLength) {
    return Status::InvalidInput("max length must be in 0.." + std::to_string(graph::kMaxLength));
  }
  if (o.vomm_insert < 0 || o.vomm_insert > markov::kMaxInsert) {
    return Status::InvalidInput("VOMM insert must be in 0.." + std::to_string(markov::kMaxInsert));
  }
  graph::SearchOptions so;
  so.max_length = o.max_length;
  so.max_expanded = o.max_expanded;
  so.memory_bytes = o.memory_bytes;
  SB_RETURN_IF_ERROR(graph::ValidateSearchOptions(so));

  EvalReport rep;
  std::vector<Route> train, held;
  for (size_t i = 0; i < routes.size(); ++i) (i % 2 == 0 ? train : held).push_back(routes[i]);
  // Training data: climbing tokens for the graphs, k3 symbols for the VOMM.
  auto sequences = ClimbSequences(train, lang);
  std::set<std::string> seen_tokens, seen_symbols;
  std::vector<std::string> train_syms, held_syms;
  for (const Route& r : train) {
    for (const Move& m : r.moves) {
      const language::MoveReading rd = lang.Read(m.text);
      if (!rd.features.parsed) continue;
      train_syms.push_back(rd.symbols.k[kSymbolSet]);
      seen_symbols.insert(rd.symbols.k[kSymbolSet]);
      seen_tokens.insert(graph::FormatToken(*ClimbToken(m.hand, rd.features)));
    }
  }
  for (const Route& r : held) {
    for (const Move& m : r.moves) {
      const language::MoveReading rd = lang.Read(m.text);
      if (rd.features.parsed) held_syms.push_back(rd.symbols.k[kSymbolSet]);
    }
  }
  rep.training_routes = static_cast<int>(train.size());
  rep.heldout_routes = static_cast<int>(held.size());
  rep.training_moves = static_cast<int>(train_syms.size());
  rep.heldout_moves = static_cast<int>(held_syms.size());
  if (train_syms.size() < 2 || held_syms.size() < 2) {
    return Status::InvalidInput(
        "too few readable moves to train and judge (need routes in both halves)");
  }
  auto g = graph::GraphModel::Train(sequences, kClimbFeatures, o.graph);
  if (!g.ok()) return g.status();
  markov::ModelSpec spec;
  spec.depth = o.depth;
  auto vomm = markov::TokenModel::FromTokens(spec, train_syms);
  if (!vomm.ok()) return vomm.status();
  auto judge = markov::TokenModel::FromTokens(spec, held_syms);
  if (!judge.ok()) return judge.status();

  rep.methods.resize(3);
  rep.methods[0].name = "astar";
  rep.methods[1].name = "greedy";
  rep.methods[2].name = "vomm";
  std::vector<const Route*> usable;
  for (const Route& r : train)
    if (r.moves.size() >= 4) usable.push_back(&r);
  for (size_t p = 0; p + 1 < usable.size() && rep.variations < o.variations; p += 2) {
    std::vector<chaos::InputRoute> in = {{"a", *usable[p]}, {"b", *usable[p + 1]}};
    auto v = chaos::Vary(std::move(in), chaos::VaryParams());
    if (!v.ok()) return v.status();
    ++rep.variations;
    const auto& moves = v->moves;
    // Per move: its state, its k3 symbol ("" when unusable).
    std::vector<std::vector<int32_t>> state(moves.size());
    std::vector<std::string> sym(moves.size());
    for (size_t j = 0; j < moves.size(); ++j) {
      if (!moves[j].source) continue;
      const language::MoveReading rd = lang.Read(moves[j].text);
      if (!rd.features.parsed) continue;
      sym[j] = rd.symbols.k[kSymbolSet];
      auto ids = g->Encode(*ClimbToken(moves[j].hand, rd.features), "move");
      if (ids.ok()) state[j] = std::move(ids).value();
    }
    for (size_t j = 0; j + 1 < moves.size(); ++j) {
      if (Continues(moves[j], moves[j + 1])) continue;
      if (state[j].empty() || state[j + 1].empty()) {
        ++rep.skipped_boundaries;
        continue;
      }
      ++rep.boundaries;
      std::vector<std::string> before, after;
      for (size_t i = 0; i <= j; ++i)
        if (!sym[i].empty()) before.push_back(sym[i]);
      for (size_t i = j + 1; i < moves.size(); ++i)
        if (!sym[i].empty()) after.push_back(sym[i]);
      const size_t cb = before.size() > static_cast<size_t>(o.depth) ? before.size() - o.depth : 0;
      const std::vector<std::string> ctx(before.begin() + cb, before.end());
      const double direct = JudgeBits(*judge, ctx, {after.front()});
      std::string example = "between '" + moves[j].text + "' (" + HandLetter(moves[j].hand) +
                            ") and '" + moves[j + 1].text + "' (" + HandLetter(moves[j + 1].hand) +
                            "):\n";
      bool astar_inserted = false;
      for (int mi = 0; mi < 2; ++mi) {
        MethodReport& m = rep.methods[mi];
        ++m.boundaries;
        graph::SearchOptions s = so;
        s.strategy = mi == 0 ? graph::Strategy::kAStar : graph::Strategy::kGreedy;
        const auto t0 = std::chrono::steady_clock::now();
        auto r = graph::Interpolate(*g, state[j], state[j + 1], s);
        m.seconds += Seconds(t0);
        if (!r.ok()) return r.status();
        m.expanded += r->stats.expanded;
        if (r->outcome == graph::Outcome::kNoPath) ++m.no_path;
        if (r->outcome == graph::Outcome::kLimit) ++m.gave_up;
        if (r->outcome != graph::Outcome::kFound) {
          example += "  " + m.name + ": " + r->reason + "\n";
          continue;
        }
        ++m.found;
        m.lengths.push_back(static_cast<int>(r->inserted.size()));
        std::vector<std::string> seq;
        example += "  " + m.name + " (" + Fixed(r->cost, 2) + " nats):";
        for (const auto& st : r->inserted) {
          const graph::Token tok = g->Decode(st);
          const std::string text = ReadableClimbMove(tok, lang);
          example += " " + text + ";";
          // The judge reads the inserted move as the grammar reads its text.
          const language::MoveReading rd = lang.Read(text.substr(2));
          const std::string s3 = rd.features.parsed ? rd.symbols.k[kSymbolSet] : "NO_PARSE";
          seq.push_back(s3);
          ++m.moves;
          m.novel_moves += seen_tokens.count(graph::FormatToken(tok)) == 0;
          m.novel_symbols += seen_symbols.count(s3) == 0;
        }
        if (r->inserted.empty()) example += " (the direct transition)";
        example += "\n";
        if (mi == 0 && !r->inserted.empty()) astar_inserted = true;
        seq.push_back(after.front());
        m.judge_bits += JudgeBits(*judge, ctx, seq);
        m.judge_direct_bits += direct;
      }
      {
        MethodReport& m = rep.methods[2];
        ++m.boundaries;
        const auto t0 = std::chrono::steady_clock::now();
        auto r = markov::SuggestSmoothing(*vomm, before, after, o.vomm_insert);
        m.seconds += Seconds(t0);
        if (!r.ok()) return r.status();
        ++m.found;
        m.lengths.push_back(static_cast<int>(r->insert.size()));
        std::vector<std::string> seq = r->insert;
        example += "  vomm:";
        for (const std::string& s3 : r->insert) {
          example += " " + lang.MoveText(s3) + ";";
          ++m.moves;
          m.novel_symbols += seen_symbols.count(s3) == 0;
        }
        if (r->insert.empty()) example += " (nothing: the direct transition)";
        example += "\n";
        seq.push_back(after.front());
        m.judge_bits += JudgeBits(*judge, ctx, seq);
        m.judge_direct_bits += direct;
      }
      if (rep.example.empty() && astar_inserted) rep.example = example;
    }
  }
  if (rep.boundaries == 0) return Status::InvalidInput("no usable boundary in the variations");
  return rep;
}

std::string FormatEvalReport(const EvalReport& r, bool timing) {
  std::string out;
  out += "training routes " + std::to_string(r.training_routes) + " (" +
         std::to_string(r.training_moves) + " readable moves), held-out routes " +
         std::to_string(r.heldout_routes) + " (" + std::to_string(r.heldout_moves) + " moves)\n";
  out += "variations " + std::to_string(r.variations) + ", boundaries " +
         std::to_string(r.boundaries) + " (skipped " + std::to_string(r.skipped_boundaries) +
         ": a blank, an unreadable move or a value the graphs never saw)\n\n";
  out +=
      "method  found            inserted>0  length mean/median/max  judge bits/transition "
      "(direct)  novel moves  novel symbols";
  out += timing ? "  ms/boundary  expanded/boundary\n" : "  expanded/boundary\n";
  for (const MethodReport& m : r.methods) {
    std::vector<int> l = m.lengths;
    std::sort(l.begin(), l.end());
    int some = 0;
    double sum = 0;
    for (int x : l) {
      some += x > 0;
      sum += x;
    }
    const double n = l.empty() ? 1.0 : static_cast<double>(l.size());
    char line[512];
    std::snprintf(line, sizeof line,
                  "%-7s %4d/%-4d %5.1f%%  %10d  %6.2f / %d / %d %18s (%s)  %5d/%-5d  %5d/%-5d",
                  m.name.c_str(), m.found, m.boundaries,
                  m.boundaries ? 100.0 * m.found / m.boundaries : 0.0, some, sum / n,
                  l.empty() ? 0 : l[l.size() / 2], l.empty() ? 0 : l.back(),
                  Fixed(m.found ? m.judge_bits / m.found : 0.0, 2).c_str(),
                  Fixed(m.found ? m.judge_direct_bits / m.found : 0.0, 2).c_str(), m.novel_moves,
                  m.moves, m.novel_symbols, m.moves);
    out += line;
    if (timing) {
      out += "  " + Fixed(m.boundaries ? 1000.0 * m.seconds / m.boundaries : 0.0, 2);
    }
    out += "  " + Fixed(m.boundaries ? static_cast<double>(m.expanded) / m.boundaries : 0.0, 0);
    if (m.no_path || m.gave_up) {
      out += "  (no path " + std::to_string(m.no_path) + ", gave up " + std::to_string(m.gave_up) +
             ")";
    }
    out += "\n";
  }
  if (!r.example.empty()) out += "\nexample boundary " + r.example;
  return out;
}

}  // namespace sb::plan
