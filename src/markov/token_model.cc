#include "markov/token_model.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <utility>

#include "base/files.h"
#include "base/hash.h"
#include "base/number.h"
#include "base/text.h"
#include "markov/bytes.h"

namespace sb::markov {
namespace {

constexpr char kMagic[8] = {'S', 'B', 'V', 'O', 'M', 'M', '\r', '\n'};
// Version 1: parameters, vocabulary, metadata, training sequence (loading
// retrains); byte-wise FNV-1a. Version 2 (written since): the same plus the
// trained state, word-wise FNV-1a (WordFnv1a64).
constexpr uint32_t kVersion1 = 1;
constexpr uint32_t kVersion = 2;
constexpr uint32_t kFlagVocabulary = 1;
constexpr uint32_t kFlagMetadata = 2;

using internal::ByteReader;
using internal::PutU32;
using internal::PutU64;

}  // namespace

Vocabulary::Vocabulary(std::vector<std::string> tokens) : tokens_(std::move(tokens)) {
  std::sort(tokens_.begin(), tokens_.end());
  tokens_.erase(std::unique(tokens_.begin(), tokens_.end()), tokens_.end());
  for (size_t i = 0; i < tokens_.size(); ++i) ids_.emplace(tokens_[i], static_cast<int32_t>(i));
}

int32_t Vocabulary::Id(std::string_view token) const {
  auto it = ids_.find(token);
  return it == ids_.end() ? unknown_id() : it->second;
}

const std::string& Vocabulary::Token(int32_t id) const {
  static const std::string kUnk = "<unk>";
  if (id < 0 || static_cast<size_t>(id) >= tokens_.size()) return kUnk;
  return tokens_[id];
}

Result<TokenModel> TokenModel::Build(const ModelSpec& spec, bool has_vocab, Vocabulary vocab,
                                     std::vector<int32_t> ids) {
  auto m = Model::Train(spec, ids);
  if (!m.ok()) return m.status();
  TokenModel tm;
  tm.model_ = std::shared_ptr<const Model>(std::move(m).value());
  tm.has_vocab_ = has_vocab;
  tm.vocab_ = std::move(vocab);
  tm.training_ = std::move(ids);
  return tm;
}

Result<TokenModel> TokenModel::FromIds(const ModelSpec& spec, std::vector<int32_t> ids) {
  return Build(spec, false, Vocabulary(), std::move(ids));
}

Result<TokenModel> TokenModel::FromTokens(ModelSpec spec, const std::vector<std::string>& tokens) {
  if (tokens.empty()) return Status::InvalidInput("no training tokens");
  return FromTokensWithVocabulary(spec, Vocabulary(tokens), tokens);
}

Result<TokenModel> TokenModel::FromTokensWithVocabulary(ModelSpec spec, const Vocabulary& vocab,
                                                        const std::vector<std::string>& tokens) {
  spec.alphabet_size = static_cast<int>(vocab.size()) + 1;
  std::vector<int32_t> ids;
  ids.reserve(tokens.size());
  for (const auto& t : tokens) ids.push_back(vocab.Id(t));
  return Build(spec, true, vocab, std::move(ids));
}

Result<std::vector<int32_t>> TokenModel::Encode(const std::vector<std::string>& tokens) const {
  std::vector<int32_t> ids;
  ids.reserve(tokens.size());
  for (size_t i = 0; i < tokens.size(); ++i) {
    if (has_vocab_) {
      ids.push_back(vocab_.Id(tokens[i]));
      continue;
    }
    int32_t v = -1;
    if (!ParseInt(tokens[i], &v) || v < 0 || v >= spec().alphabet_size) {
      return Status::InvalidInput("token " + std::to_string(i + 1) + " '" + tokens[i] +
                                  "' is not an integer in [0, " +
                                  std::to_string(spec().alphabet_size) + ")");
    }
    ids.push_back(v);
  }
  return ids;
}

std::string TokenModel::Decode(int32_t id) const {
  return has_vocab_ ? vocab_.Token(id) : std::to_string(id);
}

std::string TokenModel::Serialize() const {
  std::string out(kMagic, sizeof kMagic);
  PutU32(&out, kVersion);
  const ModelSpec& s = spec();
  PutU32(&out, static_cast<uint32_t>(s.algorithm));
  PutU32(&out, static_cast<uint32_t>(s.depth));
  PutU32(&out, static_cast<uint32_t>(s.alphabet_size));
  uint64_t alpha_bits;
  std::memcpy(&alpha_bits, &s.alpha, 8);
  PutU64(&out, alpha_bits);
  PutU32(&out, (has_vocab_ ? kFlagVocabulary : 0) | (metadata_.empty() ? 0 : kFlagMetadata));
  if (has_vocab_) {
    PutU32(&out, static_cast<uint32_t>(vocab_.size()));
    for (const auto& t : vocab_.tokens()) {
      PutU32(&out, static_cast<uint32_t>(t.size()));
      out += t;
    }
  }
  if (!metadata_.empty()) {
    PutU32(&out, static_cast<uint32_t>(metadata_.size()));
    for (const auto& [k, v] : metadata_) {
      PutU32(&out, static_cast<uint32_t>(k.size()));
      out += k;
      PutU32(&out, static_cast<uint32_t>(v.size()));
      out += v;
    }
  }
  PutU64(&out, training_.size());
  internal::PutArray(&out, training_);
  // The state section starts 8-byte aligned, so a mapped file can be used in place.
  while ((out.size() + 8) % 8 != 0) out.push_back('\0');
  const size_t len_at = out.size();
  PutU64(&out, 0);
  const size_t begin = out.size();
  model_->SaveState(&out);
  const uint64_t len = out.size() - begin;
  for (int i = 0; i < 8; ++i) out[len_at + i] = static_cast<char>((len >> (8 * i)) & 0xff);
  PutU64(&out, WordFnv1a64(out));
  return out;
}

Result<TokenModel> TokenModel::Parse(std::string_view bytes, const std::string& name) {
  auto copy = std::make_shared<const std::string>(bytes);
  const std::string_view view(*copy);
  return Parse(view, name, std::move(copy));
}

Result<TokenModel> TokenModel::Parse(std::string_view bytes, const std::string& name,
                                     std::shared_ptr<const void> backing) {
  auto bad = [&](const std::string& why) {
    return Status::InvalidInput(name + ": not a valid model file: " + why);
  };
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    return bad("wrong magic (expected an 'SBVOMM' model)");
  }
  if (bytes.size() < sizeof kMagic + 4 + 8) return bad("truncated header");
  ByteReader r(bytes.substr(sizeof kMagic, bytes.size() - sizeof kMagic - 8));
  uint32_t version = 0, alg = 0, depth = 0, ab = 0, flags = 0;
  uint64_t alpha_bits = 0;
  r.U32(&version);
  if (version != kVersion && version != kVersion1) {
    return bad("unsupported format version " + std::to_string(version) +
               " (this build reads 1 and 2)");
  }
  {
    uint64_t stored = 0;
    for (int i = 0; i < 8; ++i)
      stored |= uint64_t{static_cast<unsigned char>(bytes[bytes.size() - 8 + i])} << (8 * i);
    const std::string_view body = bytes.substr(0, bytes.size() - 8);
    const uint64_t want = version == kVersion1 ? Fnv1a64(body) : WordFnv1a64(body);
    if (stored != want) return bad("checksum mismatch (file truncated or corrupted)");
  }
  if (!r.U32(&alg) || !r.U32(&depth) || !r.U32(&ab) || !r.U64(&alpha_bits) || !r.U32(&flags)) {
    return bad("truncated header");
  }
  if (alg > 2) return bad("unknown algorithm code " + std::to_string(alg));
  if ((flags & ~(kFlagVocabulary | kFlagMetadata)) != 0) return bad("unknown flags");
  ModelSpec spec;
  spec.algorithm = static_cast<Algorithm>(alg);
  spec.depth = depth > 1000 ? 1000 : static_cast<int>(depth);
  spec.alphabet_size = ab > 100000000 ? 100000000 : static_cast<int>(ab);
  std::memcpy(&spec.alpha, &alpha_bits, 8);
  if (Status st = ValidateSpec(spec); !st.ok()) return bad(st.message());
  const bool has_vocab = (flags & kFlagVocabulary) != 0;
  std::vector<std::string> tokens;
  if (has_vocab) {
    uint32_t n = 0;
    if (!r.U32(&n)) return bad("truncated vocabulary");
    if (static_cast<uint64_t>(n) + 1 != ab) return bad("vocabulary size does not match alphabet");
    if (n > r.remaining() / 4) return bad("truncated vocabulary");
    tokens.reserve(n);
    for (uint32_t i = 0; i < n; ++i) {
      uint32_t len = 0;
      std::string_view t;
      if (!r.U32(&len) || !r.Bytes(len, &t)) return bad("truncated vocabulary");
      if (t.empty() || (i > 0 && !(tokens.back() < t))) {
        return bad("vocabulary is not sorted and distinct");
      }
      if (FindInvalidUtf8(t) != std::string_view::npos || t.find('\0') != t.npos) {
        return bad("vocabulary token " + std::to_string(i + 1) + " is not valid UTF-8");
      }
      tokens.emplace_back(t);
    }
  }
  std::map<std::string, std::string> metadata;
  if (flags & kFlagMetadata) {
    uint32_t count = 0;
    if (!r.U32(&count) || count == 0 || count > r.remaining() / 8) return bad("truncated metadata");
    std::string_view last;
    for (uint32_t i = 0; i < count; ++i) {
      uint32_t kl = 0, vl = 0;
      std::string_view k, v;
      if (!r.U32(&kl) || !r.Bytes(kl, &k) || !r.U32(&vl) || !r.Bytes(vl, &v)) {
        return bad("truncated metadata");
      }
      if (k.empty() || v.empty() || (i > 0 && !(last < k))) {
        return bad("metadata keys are not sorted, distinct and non-empty");
      }
      if (FindInvalidUtf8(k) != std::string_view::npos ||
          FindInvalidUtf8(v) != std::string_view::npos || k.find('\0') != k.npos ||
          v.find('\0') != v.npos) {
        return bad("metadata entry " + std::to_string(i + 1) + " is not valid UTF-8");
      }
      last = k;
      metadata.emplace(std::string(k), std::string(v));
    }
  }
  uint64_t n = 0;
  if (!r.U64(&n) || n > r.remaining() / 4) return bad("truncated training sequence");
  if (version == kVersion1 && r.remaining() != n * 4) {
    return bad("trailing bytes after the training sequence");
  }
  std::vector<int32_t> ids;
  r.Array(n, &ids);
  for (uint64_t i = 0; i < n; ++i) {
    const uint32_t v = static_cast<uint32_t>(ids[i]);
    if (v >= ab) return bad("symbol id out of range at position " + std::to_string(i));
    if (has_vocab && v == ab - 1) return bad("unknown-token id in the training sequence");
  }
  Vocabulary vocab(std::move(tokens));
  Result<TokenModel> tm = Status::Internal("unset");
  if (version == kVersion1) {
    tm = Build(spec, has_vocab, std::move(vocab), std::move(ids));  // retrains
  } else {
    uint64_t len = 0;
    std::string_view state, pad;
    // Zero padding up to the 8-byte aligned length field.
    const size_t at = sizeof kMagic + r.pos();
    if (!r.Bytes((8 - at % 8) % 8, &pad) || pad.find_first_not_of('\0') != std::string_view::npos) {
      return bad("truncated or bad padding before the trained state");
    }
    if (!r.U64(&len) || !r.Bytes(len, &state)) return bad("truncated trained state");
    if (r.remaining() != 0) return bad("trailing bytes after the trained state");
    auto m = Model::FromState(spec, ids, state, std::move(backing));
    if (!m.ok()) return bad(m.status().message());
    TokenModel t;
    t.model_ = std::shared_ptr<const Model>(std::move(m).value());
    t.has_vocab_ = has_vocab;
    t.vocab_ = std::move(vocab);
    t.training_ = std::move(ids);
    tm = std::move(t);
  }
  if (!tm.ok()) return bad(tm.status().message());
  tm->set_metadata(std::move(metadata));
  return tm;
}

Status SaveModel(const TokenModel& model, const std::string& path) {
  return WriteFileAtomic(path, model.Serialize());
}

Result<TokenModel> LoadModel(const std::string& path) {
  if (FindInvalidUtf8(path) != std::string_view::npos) {
    return Status::InvalidInput("model path is not valid UTF-8 (rename the file)");
  }
  // Map the file (read-only); fall back to reading it (pipes, empty files).
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  struct stat st {};
  if (fd >= 0 && ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
    const size_t size = static_cast<size_t>(st.st_size);
    void* p = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    ::close(fd);
    if (p != MAP_FAILED) {
      std::shared_ptr<const void> mapping(
          p, [size](const void* q) { ::munmap(const_cast<void*>(q), size); });
      return TokenModel::Parse(std::string_view(static_cast<const char*>(p), size), path,
                               std::move(mapping));
    }
  } else if (fd >= 0) {
    ::close(fd);
  }
  auto data = ReadFile(path);
  if (!data.ok()) return data.status();
  return TokenModel::Parse(*data, path);
}

std::vector<std::string> Tokenize(std::string_view text) {
  std::vector<std::string> out;
  size_t i = 0;
  auto ws = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
  };
  while (i < text.size()) {
    while (i < text.size() && ws(text[i])) ++i;
    size_t j = i;
    while (j < text.size() && !ws(text[j])) ++j;
    if (j > i) out.emplace_back(text.substr(i, j - i));
    i = j;
  }
  return out;
}

}  // namespace sb::markov
