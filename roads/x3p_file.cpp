#include "roads/x3p_file.hpp"

#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

#include <pugixml.hpp>
#include <zip.h>

#include "lib/core/content_hash.hpp"
#include "lib/core/errors.hpp"
#include "lib/core/memory_guard.hpp"
#include "lib/io/atomic_output.hpp"
#include "roads/text_records.hpp"
#include "wetroad/version.hpp"

namespace wr {
namespace {

constexpr const char* kX3pNamespace = "http://www.opengps.eu/2008/ISO5436_2";

constexpr const char* kMainXml = "main.xml";
constexpr const char* kVendorFile = "wetroad.json";

// libzip's words for an error code of zip_open.
std::string zip_error_text(int code) {
  zip_error_t ze;
  zip_error_init_with_code(&ze, code);
  std::string why = zip_error_strerror(&ze);
  zip_error_fini(&ze);
  return why;
}

// ---- reading ----

class ZipReader {
 public:
  explicit ZipReader(const std::string& path) : path_(path) {
    int err = 0;
    // ZIP_CHECKCONS: a damaged central directory is an error here, not garbage later.
    za_ = zip_open(path.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &err);
    if (!za_) throw InputError(path, "not a readable X3P archive (zip: " + zip_error_text(err) + ")");
    try {
      locate_main();
    } catch (...) {
      zip_discard(za_);
      throw;
    }
  }
  ~ZipReader() { zip_discard(za_); }
  ZipReader(const ZipReader&) = delete;
  ZipReader& operator=(const ZipReader&) = delete;

  // Names below are relative to main.xml's folder (ISO 25178-72 links are relative to it):
  // the archive's root, or the one top folder that zipping a folder puts everything under.
  const std::string& folder() const { return folder_; }
  std::string full(const std::string& name) const { return folder_ + name; }

  bool has(const std::string& name) const { return zip_name_locate(za_, full(name).c_str(), 0) >= 0; }

  // The entry's size as the directory states it; InputError when there is no such entry.
  std::size_t size(const std::string& name) const {
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat(za_, full(name).c_str(), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
      throw InputError(path_, "the X3P archive has no " + full(name));
    return std::size_t(st.size);
  }

  // The whole entry; a CRC mismatch (a damaged archive) surfaces as a read error.
  std::string read(const std::string& name) const {
    const std::size_t stated = size(name);
    require_memory(stated, 1, 2.0, path_, "reading " + full(name));
    std::unique_ptr<zip_file_t, decltype(&zip_fclose)> f(zip_fopen(za_, full(name).c_str(), 0), &zip_fclose);
    if (!f) throw InputError(path_, "cannot open " + name + " in the X3P archive (" + zip_strerror(za_) + ")");
    std::string bytes(stated, '\0');
    std::size_t got = 0;
    while (got < bytes.size()) {
      const zip_int64_t n = zip_fread(f.get(), bytes.data() + got, bytes.size() - got);
      if (n < 0) throw InputError(path_, "damaged X3P archive: " + name + ": " + zip_file_strerror(f.get()));
      if (n == 0) break;
      got += std::size_t(n);
    }
    char extra;
    if (got != bytes.size() || zip_fread(f.get(), &extra, 1) != 0)
      throw InputError(path_, "damaged X3P archive: " + name + " is not the size its directory says");
    return bytes;
  }

 private:
  // Finds the archive's one main.xml: at the root, or as FOLDER/main.xml under one top folder.
  // Two of them (a root one and a folder's, or two folders') would leave it to chance which
  // measurement is read: refused.
  void locate_main() {
    const zip_int64_t n = zip_get_num_entries(za_, 0);
    std::vector<std::string> found;
    for (zip_int64_t i = 0; i < n; ++i) {
      const char* raw = zip_get_name(za_, zip_uint64_t(i), 0);
      if (!raw) continue;
      const std::string name = raw;
      const std::size_t slash = name.find('/');
      if (name == kMainXml || (slash != std::string::npos && slash > 0 && name.substr(slash + 1) == kMainXml))
        found.push_back(name);
    }
    if (found.empty()) throw InputError(path_, std::string("the X3P archive has no ") + kMainXml);
    if (found.size() > 1) {
      std::string list;
      for (std::size_t i = 0; i < found.size() && i < 4; ++i) list += (i ? ", " : "") + found[i];
      if (found.size() > 4) list += ", ...";
      throw InputError(path_, "the X3P archive holds " + std::to_string(found.size()) + " main.xml files (" + list +
                                  "): one measurement per archive");
    }
    folder_ = found.front().substr(0, found.front().size() - std::strlen(kMainXml));
  }

  std::string path_;
  zip_t* za_ = nullptr;
  std::string folder_;  // "" or "FOLDER/"
};

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trimmed(const char* t) {
  std::string s(t);
  const auto a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

struct XmlContext {
  const std::string& path;
  std::string xml_name = kMainXml;  // as the archive names it (FOLDER/main.xml)
  [[noreturn]] void fail(const std::string& why) const { throw InputError(path, xml_name + ": " + why); }
  pugi::xml_node need(pugi::xml_node parent, const char* name) const {
    pugi::xml_node n = parent.child(name);
    if (!n) fail(std::string("no ") + parent.name() + "/" + name);
    return n;
  }
  std::string text(pugi::xml_node parent, const char* name) const { return trimmed(need(parent, name).child_value()); }
  double number(pugi::xml_node parent, const char* name, std::optional<double> fallback = std::nullopt) const {
    pugi::xml_node n = parent.child(name);
    if (!n) {
      if (fallback) return *fallback;
      fail(std::string("no ") + parent.name() + "/" + name);
    }
    const std::string t = trimmed(n.child_value());
    const std::optional<double> v = parse_number(t);
    if (!v || !std::isfinite(*v)) fail(std::string(parent.name()) + "/" + name + " is not a number: '" + t + "'");
    return *v;
  }
  std::size_t count(pugi::xml_node parent, const char* name) const {
    const double v = number(parent, name);
    if (!(v >= 1 && v <= 1e12 && v == std::floor(v))) fail(std::string(parent.name()) + "/" + name + " is not a positive whole number");
    return std::size_t(v);
  }
};

struct Axis {
  std::string type;  // "I" or "A"
  char data = 'D';
  double increment = 1, offset = 0;
};

Axis read_axis(const XmlContext& x, pugi::xml_node axes, const char* name) {
  pugi::xml_node n = x.need(axes, name);
  Axis a;
  a.type = x.text(n, "AxisType");
  const std::string dt = n.child("DataType") ? x.text(n, "DataType") : std::string("D");
  if (dt.size() != 1 || std::string("ILFD").find(dt[0]) == std::string::npos)
    x.fail(std::string(name) + " data type '" + dt + "' is not one of I, L, F, D");
  a.data = dt[0];
  a.increment = x.number(n, "Increment", 1.0);
  a.offset = x.number(n, "Offset", 0.0);
  return a;
}

std::size_t type_bytes(char t) { return t == 'I' ? 2 : (t == 'L' || t == 'F') ? 4 : 8; }

// The data hold as many points as the matrix declares: checked before the map is allocated,
// so that a small archive declaring a huge matrix costs nothing.
void check_point_count(const XmlContext& x, const ZipReader& zip, pugi::xml_node rec3, char type, std::size_t n) {
  if (pugi::xml_node link = rec3.child("DataLink")) {
    const std::string name = x.text(link, "PointDataLink");
    const std::size_t bytes = zip.size(name);
    if (bytes / type_bytes(type) != n || bytes % type_bytes(type) != 0)
      x.fail(name + " holds " + std::to_string(bytes) + " bytes; " + std::to_string(n) + " points of type " + type +
             " need " + std::to_string(n * type_bytes(type)));
    return;
  }
  pugi::xml_node list = rec3.child("DataList");
  if (!list) x.fail("Record3 has neither DataLink nor DataList");
  const auto data = list.children("Datum");
  const std::size_t count = std::size_t(std::distance(data.begin(), data.end()));
  if (count != n) x.fail("DataList holds " + std::to_string(count) + " points, MatrixDimension " + std::to_string(n));
}

// Little-endian raw value at point i, whatever the host's byte order.
double raw_value(const unsigned char* p, char t) {
  std::uint64_t u = 0;
  const std::size_t n = type_bytes(t);
  for (std::size_t b = 0; b < n; ++b) u |= std::uint64_t(p[b]) << (8 * b);
  switch (t) {
    case 'I': return double(std::int16_t(std::uint16_t(u)));
    case 'L': return double(std::int32_t(std::uint32_t(u)));
    case 'F': return double(std::bit_cast<float>(std::uint32_t(u)));
    default: return std::bit_cast<double>(u);
  }
}

void check_md5(const XmlContext& x, pugi::xml_node link, const char* element, const std::string& bytes, const std::string& what) {
  pugi::xml_node n = link.child(element);
  if (!n) return;
  const std::string want = lower(trimmed(n.child_value())), got = md5_hex(bytes);
  if (want != got) x.fail(what + " checksum mismatch: " + element + " says " + want + ", the data has " + got);
}

// Heights from bindata (DataLink) or inline (DataList); NaN at invalid points.
void read_points(const XmlContext& x, const ZipReader& zip, pugi::xml_node rec3, const Axis& cz, HeightMap& m) {
  const std::size_t n = m.h.size();
  if (pugi::xml_node link = rec3.child("DataLink")) {
    const std::string name = x.text(link, "PointDataLink");
    const std::string data = zip.read(name);  // its size checked by check_point_count
    const std::size_t width = type_bytes(cz.data);
    check_md5(x, link, "MD5ChecksumPointData", data, name);
    const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
    for (std::size_t i = 0; i < n; ++i) m.h[i] = cz.offset + cz.increment * raw_value(bytes + i * width, cz.data);
    if (pugi::xml_node vlink = link.child("ValidPointsLink")) {
      const std::string vname = trimmed(vlink.child_value());
      const std::string valid = zip.read(vname);
      if (valid.size() != (n + 7) / 8)
        x.fail(vname + " holds " + std::to_string(valid.size()) + " bytes; " + std::to_string(n) + " points need " +
               std::to_string((n + 7) / 8));
      check_md5(x, link, "MD5ChecksumValidPoints", valid, vname);
      for (std::size_t i = 0; i < n; ++i)
        if (!((static_cast<unsigned char>(valid[i / 8]) >> (i % 8)) & 1u)) m.h[i] = std::numeric_limits<double>::quiet_NaN();
    }
    return;
  }
  std::size_t i = 0;  // as many Datum as points: check_point_count
  for (pugi::xml_node d = rec3.child("DataList").child("Datum"); d; d = d.next_sibling("Datum"), ++i) {
    const std::string t = trimmed(d.child_value());
    if (t.empty()) {  // an empty Datum is an invalid point
      m.h[i] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const std::optional<double> v = parse_number(t);
    if (!v) x.fail("Datum " + std::to_string(i + 1) + " is not one number: '" + t + "'");
    m.h[i] = cz.offset + cz.increment * *v;
  }
}

// main.xml's own checksum (Record4): a mismatch is an error, a missing file a warning.
bool verify_main_checksum(const XmlContext& x, const ZipReader& zip, pugi::xml_node root, const std::string& xml,
                          std::vector<std::string>& warnings) {
  pugi::xml_node cf = root.child("Record4").child("ChecksumFile");
  const std::string name = cf ? trimmed(cf.child_value()) : std::string();
  if (name.empty() || !zip.has(name)) {
    warnings.push_back("no checksum file for main.xml" + (name.empty() ? std::string() : " (" + name + " is missing)") +
                       ": its integrity is not verified");
    return false;
  }
  const std::string text = zip.read(name);
  const std::string want = lower(trimmed(text.substr(0, text.find_first_of(" \t\r\n*")).c_str()));
  const std::string got = md5_hex(xml);
  if (want != got) x.fail("checksum mismatch: " + name + " says " + want + ", main.xml has " + got);
  return true;
}

}  // namespace

bool looks_like_zip(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char sig[4] = {};
  in.read(sig, 4);
  return in.gcount() == 4 && std::memcmp(sig, "PK\3\4", 4) == 0;
}

X3pContents read_x3p(const std::string& path) {
  const ZipReader zip(path);  // refuses an archive without exactly one main.xml
  const std::string xml = zip.read(kMainXml);
  const XmlContext x{path, zip.full(kMainXml)};
  pugi::xml_document doc;
  if (const pugi::xml_parse_result r = doc.load_buffer(xml.data(), xml.size()); !r)
    x.fail(std::string("not well-formed XML (") + r.description() + " at byte " + std::to_string(r.offset) + ")");
  pugi::xml_node root = doc.document_element();
  const std::string rname = root.name();
  if (rname != "ISO5436_2" && !(rname.size() > 10 && rname.ends_with(":ISO5436_2")))
    x.fail("root element <" + rname + "> is not ISO5436_2");
  // The element is ISO 5436-2's only in the standard's namespace: the same name in another
  // namespace is another format whose fields need not mean the same.
  const std::string prefix = rname.size() > 10 ? rname.substr(0, rname.size() - 10) : "";
  const std::string xmlns = prefix.empty() ? "xmlns" : "xmlns:" + prefix;
  const std::string ns = root.attribute(xmlns.c_str()).as_string();
  if (ns != kX3pNamespace)
    x.fail("root element <" + rname + "> is in the namespace \"" + ns + "\", not ISO 5436-2's \"" + kX3pNamespace + "\"");
  X3pContents out;
  out.checksums_verified = verify_main_checksum(x, zip, root, xml, out.warnings);

  pugi::xml_node rec1 = x.need(root, "Record1");
  out.feature_type = x.text(rec1, "FeatureType");
  if (out.feature_type == "PCL") x.fail("feature type PCL (a point cloud with absolute x, y) is not supported; X3P maps (SUR) and profiles (PRF) are");
  if (out.feature_type != "SUR" && out.feature_type != "PRF")
    x.fail("unsupported feature type '" + out.feature_type + "' (SUR maps and PRF profiles are read)");
  const bool profile = out.feature_type == "PRF";
  pugi::xml_node axes = x.need(rec1, "Axes");
  const Axis cx = read_axis(x, axes, "CX"), cy = read_axis(x, axes, "CY"), cz = read_axis(x, axes, "CZ");
  if (cx.type != "I" || (!profile && cy.type != "I"))
    x.fail("absolute x or y axes (AxisType A: coordinates stored per point) are not supported; incremental axes are");
  if (cz.type != "A") x.fail("CZ must be an absolute axis (AxisType A), got '" + cz.type + "'");
  if (!(cx.increment > 0) || (!profile && !(cy.increment > 0)))
    x.fail("CX and CY increments (the spacings in m) must be positive");

  pugi::xml_node rec3 = x.need(root, "Record3");
  pugi::xml_node dim = rec3.child("MatrixDimension");
  if (!dim) x.fail("Record3 has no MatrixDimension (list data, ListDimension, is not supported)");
  const std::size_t sx = x.count(dim, "SizeX"), sy = x.count(dim, "SizeY"), sz = x.count(dim, "SizeZ");
  if (sz != 1) x.fail("SizeZ = " + std::to_string(sz) + ": several layers are not supported");
  if (profile && sy != 1) x.fail("a profile (PRF) must have SizeY = 1, got " + std::to_string(sy));
  const std::size_t cells = checked_cells(sx, sy, path);
  check_point_count(x, zip, rec3, cz.data, cells);
  require_memory(cells, sizeof(double), 6.0, path, "reading this X3P surface");
  HeightMap& m = out.map;
  m = HeightMap(sx, sy, cx.increment, profile ? cx.increment : cy.increment,
                profile ? HeightMap::Kind::profile : HeightMap::Kind::map);
  m.periodic = false;
  read_points(x, zip, rec3, cz, m);
  for (double v : m.h) out.invalid += !std::isfinite(v);
  out.data_type = cz.data;
  out.x_offset = cx.offset;
  out.y_offset = profile ? 0.0 : cy.offset;
  if (pugi::xml_node rec2 = root.child("Record2")) {
    out.creator = trimmed(rec2.child_value("Creator"));
    if (out.creator.empty()) out.creator = trimmed(rec2.child("Instrument").child_value("Manufacturer"));
  }
  // wetroad's own extension: periodicity (X3P has no field for it).
  for (pugi::xml_node v = root.child("VendorSpecificID"); v; v = v.next_sibling("VendorSpecificID"))
    if (trimmed(v.child_value()) == kX3pVendorId && zip.has(kVendorFile)) {
      const auto j = nlohmann::json::parse(zip.read(kVendorFile), nullptr, false);
      if (j.is_object() && j.value("periodic", false) == true) m.periodic = true;
    }
  return out;
}

// ---- writing ----

namespace {

std::string g17(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

void add_axis(pugi::xml_node axes, const char* name, const char* type, double increment) {
  pugi::xml_node a = axes.append_child(name);
  a.append_child("AxisType").text() = type;
  a.append_child("DataType").text() = "D";
  a.append_child("Increment").text() = g17(increment).c_str();
  a.append_child("Offset").text() = "0";
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char b[32];
  std::strftime(b, sizeof b, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return b;
}

std::string main_xml(const HeightMap& map, const std::string& command, const std::string& data_md5) {
  pugi::xml_document doc;
  pugi::xml_node decl = doc.append_child(pugi::node_declaration);
  decl.append_attribute("version") = "1.0";
  decl.append_attribute("encoding") = "UTF-8";
  pugi::xml_node root = doc.append_child("p:ISO5436_2");
  root.append_attribute("xmlns:p") = kX3pNamespace;
  pugi::xml_node r1 = root.append_child("Record1");
  r1.append_child("Revision").text() = "ISO5436 - 2000";
  r1.append_child("FeatureType").text() = map.is_profile() ? "PRF" : "SUR";
  pugi::xml_node axes = r1.append_child("Axes");
  add_axis(axes, "CX", "I", map.dx);
  add_axis(axes, "CY", "I", map.dy);
  add_axis(axes, "CZ", "A", 1.0);
  pugi::xml_node r2 = root.append_child("Record2");
  const std::string now = utc_now();
  r2.append_child("Date").text() = now.c_str();
  r2.append_child("Creator").text() = (std::string("wetroad ") + kVersion).c_str();
  pugi::xml_node inst = r2.append_child("Instrument");
  inst.append_child("Manufacturer").text() = "wetroad";
  inst.append_child("Model").text() = command.c_str();
  inst.append_child("Serial").text() = "none";
  inst.append_child("Version").text() = kVersion;
  r2.append_child("CalibrationDate").text() = now.c_str();
  pugi::xml_node probe = r2.append_child("ProbingSystem");
  probe.append_child("Type").text() = "Software";
  probe.append_child("Identification").text() = (std::string("wetroad ") + command).c_str();
  r2.append_child("Comment").text() = "heights in m; wetroad's provenance in wetroad.json";
  pugi::xml_node r3 = root.append_child("Record3");
  pugi::xml_node dim = r3.append_child("MatrixDimension");
  dim.append_child("SizeX").text() = std::to_string(map.nx).c_str();
  dim.append_child("SizeY").text() = std::to_string(map.ny).c_str();
  dim.append_child("SizeZ").text() = "1";
  pugi::xml_node link = r3.append_child("DataLink");
  link.append_child("PointDataLink").text() = "bindata/data.bin";
  link.append_child("MD5ChecksumPointData").text() = data_md5.c_str();
  root.append_child("Record4").append_child("ChecksumFile").text() = "md5checksum.hex";
  root.append_child("VendorSpecificID").text() = kX3pVendorId;
  std::ostringstream s;
  doc.save(s, "  ", pugi::format_default, pugi::encoding_utf8);
  return s.str();
}

std::string little_endian_doubles(const HeightMap& map) {
  std::string out(map.h.size() * 8, '\0');
  for (std::size_t i = 0; i < map.h.size(); ++i) {
    const std::uint64_t u = std::bit_cast<std::uint64_t>(map.h[i]);
    for (int b = 0; b < 8; ++b) out[i * 8 + b] = char((u >> (8 * b)) & 0xffu);
  }
  return out;
}

void add_entry(zip_t* za, const std::string& name, const std::string& bytes, const std::string& path) {
  zip_source_t* src = zip_source_buffer(za, bytes.data(), bytes.size(), 0);
  if (!src) throw InputError(path, std::string("cannot write the X3P archive: ") + zip_strerror(za));
  const zip_int64_t idx = zip_file_add(za, name.c_str(), src, ZIP_FL_ENC_UTF_8 | ZIP_FL_OVERWRITE);
  if (idx < 0) {
    zip_source_free(src);
    throw InputError(path, std::string("cannot write the X3P archive: ") + zip_strerror(za));
  }
  // Fast deflate: heights compress little; level 1 keeps writing a 4096^2 map to seconds.
  zip_set_file_compression(za, zip_uint64_t(idx), ZIP_CM_DEFLATE, 1);
}

}  // namespace

void write_x3p(const std::string& path, const HeightMap& map, const std::string& command, const nlohmann::json& provenance) {
  const std::string data = little_endian_doubles(map);
  const std::string xml = main_xml(map, command, md5_hex(data));
  const std::string checksum = md5_hex(xml) + " *main.xml\n";
  const std::string vendor = nlohmann::json{{"periodic", map.periodic}, {"provenance", provenance}}.dump(2) + "\n";
  const std::string tmp = temporary_sibling(path);
  int err = 0;
  zip_t* za = zip_open(tmp.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  if (!za) throw InputError(path, "cannot create the X3P archive (zip: " + zip_error_text(err) + ")");
  try {
    add_entry(za, kMainXml, xml, path);
    add_entry(za, "bindata/data.bin", data, path);
    add_entry(za, "md5checksum.hex", checksum, path);
    add_entry(za, kVendorFile, vendor, path);
  } catch (...) {
    zip_discard(za);
    throw;
  }
  if (zip_close(za) != 0) {
    const std::string why = zip_strerror(za);
    zip_discard(za);
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw InputError(path, "cannot write the X3P archive: " + why);
  }
  commit_file(tmp, path);
}

}  // namespace wr
