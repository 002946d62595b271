#include "apps/workspace_tile_file.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>

namespace ccma::cli {
namespace {

constexpr char kMagic[8] = {'C', 'C', 'M', 'A', 'W', 'T', '0', '2'};
constexpr std::uint64_t kWord = 8;  // bytes of a count, a double or an i64

// Encoded bytes of a sample of a model with `controls` controls and `bodies`
// bodies whose two texts are empty: the least a sample takes.
std::uint64_t SampleBytes(std::uint64_t controls, std::uint64_t bodies) {
  const std::uint64_t vectors = 4 * kWord + (6 + controls + bodies * kPoseAmbientSize) * kWord;
  return vectors + 3 /* flags */ + 5 * kWord /* measures */ + 2 * kWord /* text lengths */ + 4 * kWord /* ints */;
}

std::uint64_t SampleBytes(const Model& model) {
  return SampleBytes(static_cast<std::uint64_t>(model.num_controls()), static_cast<std::uint64_t>(model.num_bodies()));
}

std::string Hex16(std::uint64_t x) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(x));
  return text;
}

bool AllFinite(const double* x, std::size_t n) {
  return std::all_of(x, x + n, [](double v) { return std::isfinite(v); });
}

// ---- writing -------------------------------------------------------------
class Writer {
 public:
  explicit Writer(std::uint64_t map) { Raw(map); }
  template <class T>
  void Raw(const T& x) { bytes_.append(reinterpret_cast<const char*>(&x), sizeof x); }
  void Text(const std::string& s) {
    Raw<std::uint64_t>(s.size());
    bytes_ += s;
  }
  void Doubles(const double* x, std::uint64_t n) {
    Raw(n);
    if (n > 0) bytes_.append(reinterpret_cast<const char*>(x), n * sizeof(double));
  }
  void Sample(const WorkspaceSample& s) {
    Doubles(s.pose.position.data(), 3);
    Doubles(s.pose.rpy.data(), 3);
    Raw<std::uint8_t>(s.reachable);
    Raw<std::uint8_t>(s.converged);
    Raw<std::uint8_t>(s.assembled);
    Doubles(s.controls.data(), static_cast<std::uint64_t>(s.controls.size()));
    for (double v : {s.residual_energy, s.error, s.sigma_min, s.rcond, s.max_limit_violation}) Raw(v);
    Text(s.limited_by);
    Raw<std::int64_t>(s.wave);
    Raw<std::int64_t>(s.start);
    Raw<std::int64_t>(s.tile);
    Raw<std::int64_t>(s.steps);
    Text(s.warning);
    Doubles(s.state.pose(0), static_cast<std::uint64_t>(s.state.num_bodies()) * kPoseAmbientSize);
  }
  void Samples(const std::vector<WorkspaceSample>& samples) {
    Raw<std::uint64_t>(samples.size());
    for (const WorkspaceSample& s : samples) Sample(s);
  }
  std::string Finish() {
    Raw(Fnv1a(bytes_));
    return std::move(bytes_);
  }

 private:
  std::string bytes_ = std::string(kMagic, sizeof kMagic);
};

// ---- reading: every claim checked before it is believed -------------------
// Reads `bytes` from the front; the first failure sets why_ and every read
// after it fails too.
class Reader {
 public:
  Reader(const std::string& bytes, const Model& model, const WorkspaceTileLimits& limits)
      : bytes_(bytes), model_(model), limits_(limits), sample_bytes_(SampleBytes(model)) {}

  // The header's map fingerprint is this map's (set when it is another's).
  bool OwnMap(bool* other_map) {
    std::uint64_t map = 0;
    if (!Raw(&map)) return false;
    if (map == limits_.map) return true;
    if (other_map != nullptr) *other_map = true;
    return Fail("a tile of another map (map " + Hex16(map) + ", not this map's " + Hex16(limits_.map) + ")");
  }

  bool Fail(const std::string& why) {
    if (why_.empty()) why_ = why;
    return false;
  }
  const std::string& why() const { return why_; }
  std::uint64_t remaining() const { return bytes_.size() - at_; }
  bool done() const { return at_ == bytes_.size(); }

  template <class T>
  bool Raw(T* x) {
    if (!why_.empty()) return false;
    if (remaining() < sizeof(T)) return Fail("truncated");
    std::memcpy(x, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  bool Text(std::string* s, const char* what) {
    std::uint64_t n = 0;
    if (!Raw(&n)) return false;
    if (n > kMaxTileTextBytes) return Fail(std::string(what) + " longer than " + std::to_string(kMaxTileTextBytes) + " bytes");
    if (n > remaining()) return Fail("truncated");
    s->assign(bytes_.data() + at_, n);
    at_ += n;
    return true;
  }
  bool Doubles(double* x, std::uint64_t expected, const char* what) {
    std::uint64_t n = 0;
    if (!Raw(&n)) return false;
    if (n != expected) return Fail(std::string(what) + " of size " + std::to_string(n) + ", not " + std::to_string(expected));
    if (n * sizeof(double) > remaining()) return Fail("truncated");
    if (n > 0) std::memcpy(x, bytes_.data() + at_, n * sizeof(double));
    at_ += n * sizeof(double);
    return true;
  }
  bool Flag(bool* b) {
    std::uint8_t x = 0;
    if (!Raw(&x)) return false;
    if (x > 1) return Fail("a flag that is neither 0 nor 1");
    *b = x == 1;
    return true;
  }
  // An i64 in [lo, hi].
  bool Int(long long* x, long long lo, long long hi, const char* what) {
    std::int64_t v = 0;
    if (!Raw(&v)) return false;
    if (v < lo || v > hi) return Fail(std::string(what) + " " + std::to_string(v) + " out of range");
    *x = v;
    return true;
  }
  // A count of items of at least `item_bytes` each: at most `most`, and no
  // more than the bytes that remain can hold (checked before allocating).
  bool Count(std::uint64_t* n, std::uint64_t most, std::uint64_t item_bytes, const char* what) {
    if (!Raw(n)) return false;
    if (*n > most) return Fail(std::to_string(*n) + " " + what + ", more than the tile's " + std::to_string(most));
    if (*n > remaining() / item_bytes) return Fail(std::to_string(*n) + " " + what + " in " + std::to_string(remaining()) + " bytes");
    return true;
  }

  bool Sample(WorkspaceSample* s, bool own);
  bool Samples(std::vector<WorkspaceSample>* samples, bool own);
  bool CarriedRows(std::vector<long long>* rows);

 private:
  bool Check(const WorkspaceSample& s, bool own);

  const std::string& bytes_;
  const Model& model_;
  const WorkspaceTileLimits& limits_;
  const std::uint64_t sample_bytes_;
  std::size_t at_ = sizeof kMagic;
  std::string why_;
};

bool Reader::Sample(WorkspaceSample* s, bool own) {
  const auto nc = static_cast<std::uint64_t>(model_.num_controls());
  const auto nq = static_cast<std::uint64_t>(model_.num_bodies()) * kPoseAmbientSize;
  s->controls.resize(model_.num_controls());
  s->state = State(model_.num_bodies());
  long long wave = 0, tile = 0, steps = 0;
  bool ok = Doubles(s->pose.position.data(), 3, "target position") && Doubles(s->pose.rpy.data(), 3, "target rpy") &&
            Flag(&s->reachable) && Flag(&s->converged) && Flag(&s->assembled) &&
            Doubles(s->controls.data(), nc, "controls");
  for (double* v : {&s->residual_energy, &s->error, &s->sigma_min, &s->rcond, &s->max_limit_violation}) {
    ok = ok && Raw(v);
  }
  ok = ok && Text(&s->limited_by, "limited_by") && Int(&wave, 0, limits_.map_samples, "wave") &&
       Int(&s->start, -1, limits_.map_samples - 1, "start row") && Int(&tile, 0, limits_.tiles - 1, "tile") &&
       Int(&steps, 0, INT_MAX, "step count") && Text(&s->warning, "warning") &&
       Doubles(s->state.pose(0), nq, "state");
  if (!ok) return false;
  s->wave = static_cast<int>(wave);  // in range: map_samples <= WorkspaceOptions::kMaxSamples
  s->tile = static_cast<int>(tile);
  s->steps = static_cast<int>(steps);
  return Check(*s, own);
}

// What the map needs of a sample: a finite target; finite controls and
// state where it was assembled (a later sample may start there); finite
// measures where it was reached. The tile's own samples are of this tile.
bool Reader::Check(const WorkspaceSample& s, bool own) {
  if (own && s.tile != limits_.tile) {
    return Fail("a sample of tile " + std::to_string(s.tile) + ", not " + std::to_string(limits_.tile));
  }
  if (!s.pose.position.allFinite() || !s.pose.rpy.allFinite()) return Fail("a target that is not finite");
  if (s.reachable && !(s.converged && s.assembled)) return Fail("a sample reachable but not converged and assembled");
  if (s.reachable || s.assembled) {
    const auto nq = static_cast<std::size_t>(s.state.num_bodies()) * kPoseAmbientSize;
    if (!s.controls.allFinite() || !AllFinite(s.state.pose(0), nq)) {
      return Fail("an assembled sample whose controls or state are not finite");
    }
  }
  const double measures[] = {s.residual_energy, s.error, s.sigma_min, s.rcond, s.max_limit_violation};
  if (s.reachable && !AllFinite(measures, 5)) return Fail("a reachable sample whose measures are not finite");
  return true;
}

bool Reader::Samples(std::vector<WorkspaceSample>* samples, bool own) {
  std::uint64_t n = 0;
  if (!Count(&n, static_cast<std::uint64_t>(limits_.samples), sample_bytes_, own ? "samples" : "carried samples")) {
    return false;
  }
  if (own && n != static_cast<std::uint64_t>(limits_.samples)) {
    return Fail(std::to_string(n) + " samples, not the tile's " + std::to_string(limits_.samples));
  }
  samples->resize(n);
  for (WorkspaceSample& s : *samples) {
    if (!Sample(&s, own)) return false;
  }
  return true;
}

bool Reader::CarriedRows(std::vector<long long>* rows) {
  std::uint64_t n = 0;
  // Each carried row has its sample after it: kWord + sample_bytes_ at least.
  if (!Count(&n, static_cast<std::uint64_t>(limits_.samples), kWord + sample_bytes_, "carried rows")) return false;
  rows->resize(n);
  for (std::size_t i = 0; i < rows->size(); ++i) {
    if (!Int(&(*rows)[i], 0, limits_.map_samples - 1, "carried row")) return false;
    if (i > 0 && (*rows)[i] <= (*rows)[i - 1]) return Fail("carried rows not ascending");
  }
  return true;
}

}  // namespace

WorkspaceTileLimits WorkspaceTileLimitsFor(const Model& model, const std::vector<WorkspaceTile>& tiles, int tile,
                                           std::uint64_t map) {
  WorkspaceTileLimits limits;
  limits.tile = tile;
  limits.map = map;
  limits.samples = static_cast<long long>(tiles.at(static_cast<std::size_t>(tile)).rows.size());
  for (const WorkspaceTile& t : tiles) limits.map_samples += static_cast<long long>(t.rows.size());
  limits.tiles = static_cast<int>(tiles.size());
  // Samples and as many carried ones (each with its row), framing (the
  // fingerprint, three counts) and checksum.
  const auto s = static_cast<std::uint64_t>(limits.samples);
  const std::uint64_t per_sample = SampleBytes(model) + kTileTextBytesPerSample;
  limits.max_bytes = static_cast<std::size_t>(sizeof kMagic + 5 * kWord + s * (2 * per_sample + kWord));
  return limits;
}

std::string EncodeWorkspaceTile(const WorkspaceTileResult& result, std::uint64_t map) {
  Writer w(map);
  w.Samples(result.samples);
  w.Raw<std::uint64_t>(result.carried_rows.size());
  for (long long row : result.carried_rows) w.Raw<std::int64_t>(row);
  w.Samples(result.carried);
  return w.Finish();
}

std::optional<WorkspaceTileResult> DecodeWorkspaceTile(const std::string& bytes, const Model& model,
                                                       const WorkspaceTileLimits& limits, std::string* why,
                                                       bool* other_map) {
  if (other_map != nullptr) *other_map = false;
  if (bytes.size() < sizeof kMagic + kWord || bytes.compare(0, sizeof kMagic, kMagic, sizeof kMagic) != 0) {
    *why = "not a tile file (no CCMAWT02 header)";
    return std::nullopt;
  }
  if (bytes.size() > limits.max_bytes) {
    *why = std::to_string(bytes.size()) + " bytes, more than a tile of this map can take (" +
           std::to_string(limits.max_bytes) + ")";
    return std::nullopt;
  }
  std::uint64_t sum = 0;
  std::memcpy(&sum, bytes.data() + bytes.size() - sizeof sum, sizeof sum);
  const std::string body = bytes.substr(0, bytes.size() - sizeof sum);
  if (Fnv1a(body) != sum) {
    *why = "checksum mismatch";
    return std::nullopt;
  }
  Reader in(body, model, limits);
  WorkspaceTileResult out;
  const bool ok = in.OwnMap(other_map) && in.Samples(&out.samples, true) && in.CarriedRows(&out.carried_rows) &&
                  in.Samples(&out.carried, false);
  if (ok && out.carried.size() != out.carried_rows.size()) in.Fail("carried samples without their rows");
  if (ok && !in.done()) in.Fail("bytes after the last sample");
  if (!in.why().empty()) {
    *why = in.why();
    return std::nullopt;
  }
  return out;
}

}  // namespace ccma::cli
