#include "lib/fem/contact_checkpoint.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "lib/core/errors.hpp"

namespace wr {
namespace {

constexpr const char* kFormat = "wetroad-contact-checkpoint 1";

struct Fnv {
  std::uint64_t h = 1469598103934665603ull;
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
  }
  template <class T>
  void value(T v) {
    static_assert(std::is_arithmetic_v<T>);
    bytes(&v, sizeof v);
  }
};

// Binary fields, in the machine's own byte order (a checkpoint is read back where it was written).
class Writer {
 public:
  template <class T>
  void put(T v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.write(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void put(const std::vector<T>& v) {
    put(std::uint64_t(v.size()));
    out_.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(T)));
  }
  void put(const std::string& s) {
    put(std::uint64_t(s.size()));
    out_.write(s.data(), std::streamsize(s.size()));
  }
  std::string str() const { return out_.str(); }

 private:
  std::ostringstream out_;
};

class Reader {
 public:
  Reader(std::string data, std::string name) : data_(std::move(data)), name_(std::move(name)) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    take(&v, sizeof v);
    return v;
  }
  template <class T>
  void get(std::vector<T>& v) {
    const auto n = get<std::uint64_t>();
    if (n > (data_.size() - at_) / sizeof(T)) fail();
    v.resize(std::size_t(n));
    take(v.data(), std::size_t(n) * sizeof(T));
  }
  void get(std::string& s) {
    const auto n = get<std::uint64_t>();
    if (n > data_.size() - at_) fail();
    s.assign(data_, at_, std::size_t(n));
    at_ += std::size_t(n);
  }
  bool done() const { return at_ == data_.size(); }
  [[noreturn]] void fail() const { throw InputError("--restart", name_ + ": truncated or not a checkpoint of this version"); }

 private:
  void take(void* p, std::size_t n) {
    if (n > data_.size() - at_) fail();
    std::memcpy(p, data_.data() + at_, n);
    at_ += n;
  }
  std::string data_, name_;
  std::size_t at_ = 0;
};

void put_step(Writer& w, const ContactStep& s) {
  for (double v : {s.uz, s.ux, s.fz, s.fx, s.fy, s.area_fraction, s.contact_area, s.sigma_star, s.mu, s.separation,
                   s.max_penetration, s.penetration_x, s.penetration_y, s.predictor_ratio, s.coarse_wall_s, s.wall_s,
                   s.wall_linearise, s.wall_rotate, s.wall_solve, s.mu_drift})
    w.put(v);
  w.put(std::uint64_t(s.nodes_over_penetration));
  for (int v : {s.signorini_iterations, s.active_set_iterations, s.linear_iterations, s.extrapolations, s.rejected_jumps,
                s.failed_attempts, s.coarse_iterations, int(s.coarse_converged), int(s.converged)})
    w.put(std::int32_t(v));
  w.put(s.message);
  for (const auto* v : {&s.history, &s.mu_history, &s.face_pressure, &s.face_gap, &s.face_status}) w.put(*v);
}

ContactStep get_step(Reader& r) {
  ContactStep s;
  for (double* v : {&s.uz, &s.ux, &s.fz, &s.fx, &s.fy, &s.area_fraction, &s.contact_area, &s.sigma_star, &s.mu,
                    &s.separation, &s.max_penetration, &s.penetration_x, &s.penetration_y, &s.predictor_ratio,
                    &s.coarse_wall_s, &s.wall_s, &s.wall_linearise, &s.wall_rotate, &s.wall_solve, &s.mu_drift})
    *v = r.get<double>();
  s.nodes_over_penetration = std::size_t(r.get<std::uint64_t>());
  int coarse_converged = 0, converged = 0;
  for (int* v : {&s.signorini_iterations, &s.active_set_iterations, &s.linear_iterations, &s.extrapolations,
                 &s.rejected_jumps, &s.failed_attempts, &s.coarse_iterations, &coarse_converged, &converged})
    *v = r.get<std::int32_t>();
  s.coarse_converged = coarse_converged != 0;
  s.converged = converged != 0;
  r.get(s.message);
  for (auto* v : {&s.history, &s.mu_history, &s.face_pressure, &s.face_gap, &s.face_status}) r.get(*v);
  return s;
}

void put_state(Writer& w, const BlockState& s) {
  w.put(s.u);
  w.put(s.active);
  w.put(s.lambda);
  w.put(s.softening_scale);
}

BlockState get_state(Reader& r) {
  BlockState s;
  r.get(s.u);
  r.get(s.active);
  r.get(s.lambda);
  s.softening_scale = r.get<double>();
  return s;
}

void put_target(Writer& w, const LoadTarget& t) {
  w.put(t.uz);
  w.put(t.ux);
  w.put(std::int32_t(t.cutbacks_left));
}

LoadTarget get_target(Reader& r) {
  LoadTarget t;
  t.uz = r.get<double>();
  t.ux = r.get<double>();
  t.cutbacks_left = r.get<std::int32_t>();
  return t;
}

// Writes `data` to `path` through a temporary file and a rename (never half a file).
void write_file(const std::string& path, const std::string& data) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f.write(data.data(), std::streamsize(data.size()));
    f.flush();
    if (!f) throw std::runtime_error(path + ": cannot write the checkpoint");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error(path + ": cannot write the checkpoint (" + ec.message() + ")");
}

std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError("--restart", path + ": cannot read the checkpoint");
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string slot_file(const std::string& path, int slot, const std::string& part) {
  return path + "." + std::to_string(slot) + "." + part;
}

}  // namespace

std::uint64_t contact_fingerprint(const HeightMap& ob, const ContactTestOptions& o) {
  Fnv f;
  f.value(ob.nx);
  f.value(ob.ny);
  f.value(ob.dx);
  f.value(ob.dy);
  f.bytes(ob.h.data(), ob.h.size() * sizeof(double));
  for (double v : {o.uz, o.height, o.young, o.poisson, o.curvature, o.damping, o.ksp_rtol, o.facet_band,
                   o.block_normals, o.rms_slope})
    f.value(v);
  // What a restart may change (RestartableOptions): the shear's end and step count (the plan is
  // extended from the last converged step), except when shearing to the peak, whose plan adapts
  // as it goes; the cutbacks, --tol and --max-penetration of the steps to come.
  if (o.to_peak) {
    f.value(o.ux);
    f.value(o.shear_steps);
  }
  for (int v : {int(o.shear), o.normal_steps, int(o.to_peak), o.refine, o.coarse_refine, o.layers_per_level,
                o.max_coarsenings, int(o.follow_geometry), int(o.iteration), o.extrapolate_every, int(o.face_modes),
                o.max_iterations, int(o.facet_normals), int(o.amg), int(o.solver), int(o.secant_predictor)})
    f.value(v);
  return f.h;
}

void write_contact_checkpoint(const std::string& path, const ContactCheckpoint& c, MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  // The generation: the converged steps so far, so consecutive checkpoints alternate slots.
  const std::uint64_t generation = c.steps.size();
  const int slot = int(generation % 2);
  int ok = 1;
  std::string error;
  try {
    Writer w;
    put_state(w, c.last_state);
    put_state(w, c.prev_state);
    write_file(slot_file(path, slot, "rank" + std::to_string(rank)), w.str());
    if (rank == 0) {
      Writer s;
      s.put(std::uint64_t(c.next));
      s.put(std::uint64_t(c.plan.size()));
      for (const LoadTarget& t : c.plan) put_target(s, t);
      put_target(s, c.last);
      put_target(s, c.prev);
      s.put(std::int32_t(c.first_shear_iterations));
      s.put(std::uint64_t(c.steps.size()));
      for (const ContactStep& st : c.steps) put_step(s, st);
      write_file(slot_file(path, slot, "shared"), s.str());
    }
  } catch (const std::exception& e) {
    ok = 0;
    error = e.what();
  }
  MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_LAND, comm);
  if (!ok) throw std::runtime_error(error.empty() ? path + ": another rank could not write its checkpoint" : error);
  if (rank == 0) {
    char index[320];
    std::snprintf(index, sizeof index, "%s\ngeneration %llu\nslot %d\nranks %d\nfingerprint %016llx\nshear %a %d\ncutbacks %d\ntol %a\nmax-penetration %a\n",
                  kFormat, static_cast<unsigned long long>(generation), slot, ranks,
                  static_cast<unsigned long long>(c.fingerprint), c.options.ux, c.options.shear_steps,
                  c.options.max_cutbacks, c.options.tolerance, c.options.max_penetration);
    write_file(path, index);
  }
  MPI_Barrier(comm);
}

ContactCheckpoint read_contact_checkpoint(const std::string& path, std::uint64_t fingerprint, MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  std::istringstream index(read_file(path));
  std::string format;
  std::getline(index, format);
  if (format != kFormat) throw InputError("--restart", path + ": not a wetroad contact checkpoint");
  std::string key;
  unsigned long long generation = 0, fp = 0;
  int slot = -1, written_ranks = 0;
  index >> key >> generation >> key >> slot >> key >> written_ranks >> key >> std::hex >> fp >> std::dec;
  RestartableOptions ro;
  const auto hex_double = [&](const char* name, double& v) {  // "name value", value as written by %a
    std::string k, text;
    index >> k >> text;
    char* end = nullptr;
    v = std::strtod(text.c_str(), &end);
    return index && k == name && end != text.c_str() && !*end;
  };
  bool ok = hex_double("shear", ro.ux);
  index >> ro.shear_steps >> key >> ro.max_cutbacks;
  ok = ok && index && key == "cutbacks" && ro.max_cutbacks >= 0;
  ok = ok && hex_double("tol", ro.tolerance) && hex_double("max-penetration", ro.max_penetration);
  if (!ok || slot < 0 || slot > 1) throw InputError("--restart", path + ": a damaged checkpoint index");
  if (written_ranks != ranks)
    throw InputError("--restart", path + ": written by " + std::to_string(written_ranks) + " ranks, restarted on " +
                                      std::to_string(ranks) + " (the block's partition must be the same)");
  if (fp != fingerprint)
    throw InputError("--restart", path + ": written by a run of another surface or other options (a restart takes "
                                        "the same surface and contact options as the run that wrote it)");
  ContactCheckpoint c;
  c.fingerprint = fp;
  c.ranks = ranks;
  c.options = ro;
  Reader r(read_file(slot_file(path, slot, "rank" + std::to_string(rank))), path);
  c.last_state = get_state(r);
  c.prev_state = get_state(r);
  if (!r.done()) r.fail();
  Reader s(read_file(slot_file(path, slot, "shared")), path);
  c.next = std::size_t(s.get<std::uint64_t>());
  const auto plan = s.get<std::uint64_t>();
  if (plan > 1000000) s.fail();
  for (std::uint64_t k = 0; k < plan; ++k) c.plan.push_back(get_target(s));
  c.last = get_target(s);
  c.prev = get_target(s);
  c.first_shear_iterations = s.get<std::int32_t>();
  const auto steps = s.get<std::uint64_t>();
  if (steps != generation || c.next > c.plan.size()) s.fail();
  for (std::uint64_t k = 0; k < steps; ++k) c.steps.push_back(get_step(s));
  if (!s.done()) s.fail();
  return c;
}

}  // namespace wr
