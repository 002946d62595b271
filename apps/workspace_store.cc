#include "apps/workspace_store.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "apps/cli.h"

namespace ccma::cli {
namespace {

constexpr char kMagic[8] = {'C', 'C', 'M', 'A', 'W', 'T', '0', '1'};
// Bounds on what a tile file may claim before anything is allocated.
constexpr std::uint64_t kMaxTileSamples = 100000000;
constexpr std::uint64_t kMaxTextBytes = 1 << 20;

std::uint64_t Fnv1a(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}

std::string Hex(std::uint64_t x) {
  std::ostringstream out;
  out << std::hex << x;
  return out.str();
}

// ---- writing -------------------------------------------------------------
class Writer {
 public:
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

// ---- reading: every claim checked against the model and the bounds --------
class Reader {
 public:
  Reader(const std::string& bytes, const Model& model) : bytes_(bytes), model_(model) {}
  template <class T>
  bool Raw(T* x) {
    if (at_ + sizeof(T) > bytes_.size()) return false;
    std::memcpy(x, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  bool Text(std::string* s) {
    std::uint64_t n = 0;
    if (!Raw(&n) || n > kMaxTextBytes || at_ + n > bytes_.size()) return false;
    s->assign(bytes_.data() + at_, n);
    at_ += n;
    return true;
  }
  bool Doubles(double* x, std::uint64_t expected) {
    std::uint64_t n = 0;
    if (!Raw(&n) || n != expected || at_ + n * sizeof(double) > bytes_.size()) return false;
    if (n > 0) std::memcpy(x, bytes_.data() + at_, n * sizeof(double));
    at_ += n * sizeof(double);
    return true;
  }
  bool Sample(WorkspaceSample* s) {
    std::uint8_t flags[3];
    std::int64_t ints[4];
    s->controls.resize(model_.num_controls());
    s->state = State(model_.num_bodies());
    bool ok = Doubles(s->pose.position.data(), 3) && Doubles(s->pose.rpy.data(), 3) && Raw(&flags[0]) &&
              Raw(&flags[1]) && Raw(&flags[2]) &&
              Doubles(s->controls.data(), static_cast<std::uint64_t>(model_.num_controls()));
    for (double* v : {&s->residual_energy, &s->error, &s->sigma_min, &s->rcond, &s->max_limit_violation}) {
      ok = ok && Raw(v);
    }
    ok = ok && Text(&s->limited_by) && Raw(&ints[0]) && Raw(&ints[1]) && Raw(&ints[2]) && Raw(&ints[3]) &&
         Text(&s->warning) &&
         Doubles(s->state.pose(0), static_cast<std::uint64_t>(model_.num_bodies()) * kPoseAmbientSize);
    s->reachable = flags[0] != 0;
    s->converged = flags[1] != 0;
    s->assembled = flags[2] != 0;
    s->wave = static_cast<int>(ints[0]);
    s->start = ints[1];
    s->tile = static_cast<int>(ints[2]);
    s->steps = static_cast<int>(ints[3]);
    return ok;
  }
  bool Samples(std::vector<WorkspaceSample>* samples) {
    std::uint64_t n = 0;
    if (!Raw(&n) || n > kMaxTileSamples) return false;
    samples->resize(n);
    for (WorkspaceSample& s : *samples) {
      if (!Sample(&s)) return false;
    }
    return true;
  }
  std::size_t at() const { return at_; }

 private:
  const std::string& bytes_;
  const Model& model_;
  std::size_t at_ = sizeof kMagic;
};

bool Parse(const std::string& bytes, const Model& model, WorkspaceTileResult* out) {
  if (bytes.size() < sizeof kMagic + sizeof(std::uint64_t) || bytes.compare(0, sizeof kMagic, kMagic, sizeof kMagic) != 0) {
    return false;
  }
  std::uint64_t sum = 0;
  std::memcpy(&sum, bytes.data() + bytes.size() - sizeof sum, sizeof sum);
  const std::string body = bytes.substr(0, bytes.size() - sizeof sum);
  if (Fnv1a(body) != sum) return false;
  Reader in(body, model);
  std::uint64_t carried = 0;
  if (!in.Samples(&out->samples) || !in.Raw(&carried) || carried > kMaxTileSamples) return false;
  out->carried_rows.resize(carried);
  for (long long& row : out->carried_rows) {
    std::int64_t r = 0;
    if (!in.Raw(&r)) return false;
    row = r;
  }
  return in.Samples(&out->carried) && in.at() == body.size();
}

}  // namespace

WorkspaceStore::WorkspaceStore(const std::string& dir, const Model& model, const std::string& key_text, int tiles)
    : dir_(dir), model_(model) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_)) throw UsageError("--store: cannot create the directory '" + dir_ + "'");
  const nlohmann::json want = {{"ccma_workspace_store", 1}, {"key", Hex(Fnv1a(key_text))}, {"tiles", tiles}};
  const std::string manifest = dir_ + "/store.json";
  if (fs::exists(manifest)) {
    std::ifstream in(manifest);
    const nlohmann::json have = nlohmann::json::parse(in, nullptr, false);
    if (have != want) {
      throw UsageError("--store: '" + dir_ + "' holds another map (other model, ranges or options): use a new "
                       "directory, or delete this one to start again");
    }
    return;
  }
  std::ofstream out(manifest + ".tmp");
  out << want.dump() << "\n";
  out.close();
  fs::rename(manifest + ".tmp", manifest, ec);
  if (!out || ec) throw UsageError("--store: cannot write '" + manifest + "'");
}

std::string WorkspaceStore::TilePath(int tile) const { return dir_ + "/tile_" + std::to_string(tile) + ".bin"; }

bool WorkspaceStore::Load(int tile, WorkspaceTileResult* out) {
  std::ifstream in(TilePath(tile), std::ios::binary);
  if (!in) return false;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!Parse(bytes, model_, out)) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::cerr << "ccma workspace: --store: " << TilePath(tile) << " is damaged; computing the tile again\n";
    return false;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  ++loaded_;
  return true;
}

void WorkspaceStore::Save(int tile, const WorkspaceTileResult& result) {
  Writer w;
  w.Samples(result.samples);
  w.Raw<std::uint64_t>(result.carried_rows.size());
  for (long long row : result.carried_rows) w.Raw<std::int64_t>(row);
  w.Samples(result.carried);
  const std::string bytes = w.Finish();
  const std::string path = TilePath(tile), tmp = path + ".tmp";
  std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  std::error_code ec;
  if (out) std::filesystem::rename(tmp, path, ec);
  if (!out || ec) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::cerr << "ccma workspace: --store: could not write " << path << " (the map goes on without it)\n";
  }
}

}  // namespace ccma::cli
