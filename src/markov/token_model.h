// A trained model together with its token vocabulary and training sequence,
// and the versioned binary model file format (docs/formats.md, "Markov model
// files").
#ifndef SB_MARKOV_TOKEN_MODEL_H_
#define SB_MARKOV_TOKEN_MODEL_H_

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "markov/model.h"

namespace sb::markov {

// Token <-> id mapping of a string-token model. Ids 0..n-1 are the distinct
// training tokens in byte-wise ascending order; id n is reserved for
// tokens the model has never seen ("<unk>"), which is never trained, so
// the model's alphabet is n+1. Value type; thread-compatible.
class Vocabulary {
 public:
  Vocabulary() = default;
  // From distinct tokens (sorted and deduplicated here).
  explicit Vocabulary(std::vector<std::string> tokens);

  size_t size() const { return tokens_.size(); }
  // Id of the reserved unknown token (== size()).
  int32_t unknown_id() const { return static_cast<int32_t>(tokens_.size()); }
  // Id of `token`, or unknown_id().
  int32_t Id(std::string_view token) const;
  // Token of `id`; "<unk>" for unknown_id() or out-of-range ids.
  const std::string& Token(int32_t id) const;
  const std::vector<std::string>& tokens() const { return tokens_; }

 private:
  std::vector<std::string> tokens_;
  std::map<std::string, int32_t, std::less<>> ids_;
};

// A model as stored in a model file: its spec, the training sequence (the
// model is a deterministic function of it) and, for string tokens, the
// vocabulary. Immutable after construction; const methods are thread-safe.
class TokenModel {
 public:
  // Trains on integer ids in [0, spec.alphabet_size) (no vocabulary).
  // Errors: kInvalidInput (bad spec, id out of range).
  static Result<TokenModel> FromIds(const ModelSpec& spec, std::vector<int32_t> ids);
  // Trains on string tokens: builds the vocabulary, sets spec.alphabet_size
  // to vocabulary size + 1 (the unknown id). Errors: kInvalidInput (bad
  // spec, no tokens).
  static Result<TokenModel> FromTokens(ModelSpec spec, const std::vector<std::string>& tokens);
  // Trains on tokens with a given vocabulary (tokens not in it become the
  // unknown id). Used by cross-validation so that models share an alphabet.
  static Result<TokenModel> FromTokensWithVocabulary(ModelSpec spec, const Vocabulary& vocab,
                                                     const std::vector<std::string>& tokens);

  const Model& model() const { return *model_; }
  const ModelSpec& spec() const { return model_->spec(); }
  bool has_vocabulary() const { return has_vocab_; }
  const Vocabulary& vocabulary() const { return vocab_; }
  const std::vector<int32_t>& training() const { return training_; }

  // Free key/value metadata stored in the model file, e.g. "symbol_set" =
  // "k3" (which symbol set the tokens are) and "grammar" = "climbing" (which
  // grammar made them); route-plan smoothing reads both. Keys and values are
  // non-empty UTF-8 without NUL. Set it before saving; not thread-safe.
  const std::map<std::string, std::string>& metadata() const { return metadata_; }
  void set_metadata(std::map<std::string, std::string> m) { metadata_ = std::move(m); }

  // Maps input tokens to ids. With a vocabulary: unknown tokens map to the
  // unknown id. Without: tokens must be integers in [0, K); otherwise
  // kInvalidInput naming the token and its index.
  Result<std::vector<int32_t>> Encode(const std::vector<std::string>& tokens) const;
  // The token text of an id (its decimal number without a vocabulary).
  std::string Decode(int32_t id) const;

  // The model file bytes (format version 1). Deterministic.
  std::string Serialize() const;
  // Parses model file bytes and rebuilds the model (format 2: from the
  // stored trained state; format 1: by retraining). `name` prefixes errors.
  // Errors: kInvalidInput for a wrong magic, unsupported version, bad
  // checksum, truncated or inconsistent content, a vocabulary token or
  // metadata entry that is not valid UTF-8. Never crashes on any input.
  // Copies `bytes` when the model needs them (DE-CTW uses its state in place).
  static Result<TokenModel> Parse(std::string_view bytes, const std::string& name);
  // The same over bytes owned by `backing`, which the model may keep alive
  // instead of copying (LoadModel maps the file and passes the mapping).
  static Result<TokenModel> Parse(std::string_view bytes, const std::string& name,
                                  std::shared_ptr<const void> backing);

 private:
  TokenModel() = default;
  static Result<TokenModel> Build(const ModelSpec& spec, bool has_vocab, Vocabulary vocab,
                                  std::vector<int32_t> ids);
  std::shared_ptr<const Model> model_;
  bool has_vocab_ = false;
  Vocabulary vocab_;
  std::vector<int32_t> training_;
  std::map<std::string, std::string> metadata_;
};

// Writes a model file atomically. Errors: kIoError.
Status SaveModel(const TokenModel& model, const std::string& path);
// Reads and parses a model file; the file is mapped into memory read-only
// and a DE-CTW model reads its trained state from the mapping (nothing is
// copied or retrained). Errors: kNotFound / kIoError / kInvalidInput (also
// for a path that is not valid UTF-8).
Result<TokenModel> LoadModel(const std::string& path);

// Splits text into whitespace-separated tokens (space, tab, CR, LF).
std::vector<std::string> Tokenize(std::string_view text);

}  // namespace sb::markov

#endif  // SB_MARKOV_TOKEN_MODEL_H_
