#include "roads/surface_file.hpp"

#include <algorithm>
#include <cctype>

#include "lib/core/errors.hpp"
#include "lib/io/hdf5_file.hpp"
#include "roads/x3p_file.hpp"

namespace wr {

SurfaceFormat output_format(const std::string& path, const std::string& format) {
  if (format == "hdf5") return SurfaceFormat::hdf5;
  if (format == "x3p") return SurfaceFormat::x3p;
  if (format != "auto") throw InputError("--format", "must be auto, hdf5 or x3p (got '" + format + "')");
  std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".x3p" ? SurfaceFormat::x3p : SurfaceFormat::hdf5;
}

void write_surface_file(const std::string& path, const HeightMap& map,
                        const std::optional<SynthesisRecord>& synthesis, const nlohmann::json& provenance,
                        SurfaceFormat format) {
  if (format == SurfaceFormat::x3p) {
    nlohmann::json p = provenance;
    if (synthesis)
      p["synthesis"] = {{"h0", synthesis->psd.h0}, {"hurst", synthesis->psd.hurst}, {"qL", synthesis->psd.qL},
                        {"q0", synthesis->psd.q0}, {"q1", synthesis->psd.q1}, {"q1_cut", synthesis->psd.q1_cut},
                        {"plateau_k", synthesis->psd.k}, {"seed", synthesis->seed},
                        {"oversample", synthesis->oversample}, {"sampling", sampling_name(synthesis->sampling)}};
    write_x3p(path, map, provenance.value("command", std::string("wetroad")), p);
    return;
  }
  Hdf5Writer w(path);
  const std::string ds = map.is_profile() ? "/profile" : "/height";
  if (map.is_profile())
    w.write_vector(ds, map.h.data(), map.h.size());
  else
    w.write_matrix(ds, map.h.data(), map.ny, map.nx);
  w.write_attr(ds, "dx", map.dx);
  w.write_attr(ds, "dy", map.dy);
  w.write_attr(ds, "unit", std::string("m"));
  w.write_attr(ds, "periodic", static_cast<std::int64_t>(map.periodic ? 1 : 0));
  if (synthesis) {
    const auto& s = *synthesis;
    w.create_group("/synthesis");
    w.write_attr("/synthesis", "h0", s.psd.h0);
    w.write_attr("/synthesis", "hurst", s.psd.hurst);
    w.write_attr("/synthesis", "qL", s.psd.qL);
    w.write_attr("/synthesis", "q0", s.psd.q0);
    w.write_attr("/synthesis", "q1", s.psd.q1);
    w.write_attr("/synthesis", "q1_cut", s.psd.q1_cut);
    w.write_attr("/synthesis", "plateau_k", s.psd.k);
    w.write_attr("/synthesis", "plateau_k_eq44", s.k_eq44);
    w.write_attr("/synthesis", "h0_eq44_on_lattice", s.h0_eq44_on_lattice);
    w.write_attr("/synthesis", "seed", static_cast<std::int64_t>(s.seed));
    w.write_attr("/synthesis", "oversample", static_cast<std::int64_t>(s.oversample));
    w.write_attr("/synthesis", "sampling", std::string(sampling_name(s.sampling)));
  }
  w.write_attr("/", "provenance", provenance.dump());
  w.commit();
}

}  // namespace wr
