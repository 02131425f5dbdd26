// A Collada character's surface in the file's <vertices> order
// (collada_vertices.h). The corner order replicates assimp 5.2's
// ColladaParser::ReadPrimitives/CopyVertex: per primitive element
// (<triangles>, <polylist>, <polygons>, <lines>, <linestrips>, <trifans>,
// <tristrips>) in file order, per <p>, the corners as its faces list them;
// assimp makes one mesh per element that has faces, named by the geometry's
// id. The XML reader below reads elements, attributes and text (comments,
// processing instructions, DOCTYPE and CDATA handled), no more.
#include "character/collada_vertices.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include "snh/error.h"

namespace snh::detail {
namespace {

struct XmlElement {
  std::string name;  // without a namespace prefix
  std::vector<std::pair<std::string, std::string>> attributes;
  std::string text;  // the element's own character data, entities decoded
  std::vector<XmlElement> children;

  std::string attribute(const std::string& key) const {
    for (const auto& [k, v] : attributes)
      if (k == key) return v;
    return "";
  }
  bool has(const std::string& key) const {
    for (const auto& a : attributes)
      if (a.first == key) return true;
    return false;
  }
  const XmlElement* child(const std::string& n) const {
    for (const XmlElement& e : children)
      if (e.name == n) return &e;
    return nullptr;
  }
};

class XmlReader {
 public:
  explicit XmlReader(const std::string& text) : s_(text) {}

  XmlElement document() {
    misc();
    if (!at("<")) fail("no root element");
    XmlElement root = element(0);
    return root;
  }

 private:
  const std::string& s_;
  size_t i_ = 0;

  [[noreturn]] void fail(const std::string& what) const {
    throw Error("XML at byte " + std::to_string(i_) + ": " + what);
  }
  bool at(const char* p) const { return s_.compare(i_, std::strlen(p), p) == 0; }
  void skip_past(const char* end) {
    const size_t k = s_.find(end, i_);
    if (k == std::string::npos) fail(std::string("no closing ") + end);
    i_ = k + std::strlen(end);
  }
  void spaces() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  // Comments, processing instructions and a DOCTYPE (with its internal subset).
  void misc() {
    for (;;) {
      spaces();
      if (at("<?")) {
        skip_past("?>");
      } else if (at("<!--")) {
        skip_past("-->");
      } else if (at("<!") && !at("<![CDATA[")) {
        int depth = 0;
        for (; i_ < s_.size(); ++i_) {
          if (s_[i_] == '[') ++depth;
          if (s_[i_] == ']') --depth;
          if (s_[i_] == '>' && depth <= 0) break;
        }
        if (i_ >= s_.size()) fail("unterminated declaration");
        ++i_;
      } else {
        return;
      }
    }
  }
  std::string name() {
    const size_t b = i_;
    while (i_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[i_])) && s_[i_] != '>' && s_[i_] != '/' &&
           s_[i_] != '=')
      ++i_;
    if (i_ == b) fail("expected a name");
    return s_.substr(b, i_ - b);
  }
  static std::string local(const std::string& n) {
    const size_t colon = n.find(':');
    return colon == std::string::npos ? n : n.substr(colon + 1);
  }
  static void append_utf8(std::string& out, unsigned long c) {
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else if (c < 0x800) {
      out += static_cast<char>(0xC0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      out += static_cast<char>(0xE0 | (c >> 12));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (c >> 18));
      out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    }
  }
  // Character data up to `stop` (exclusive), entities decoded.
  void decode(size_t stop, std::string& out) {
    while (i_ < stop) {
      if (s_[i_] != '&') {
        out += s_[i_++];
        continue;
      }
      // A bare '&' (no entity) is kept as it is, as assimp's XML parser does.
      const size_t semi = s_.find(';', i_);
      if (semi == std::string::npos || semi > stop) {
        out += s_[i_++];
        continue;
      }
      const std::string e = s_.substr(i_ + 1, semi - i_ - 1);
      if (e == "lt") {
        out += '<';
      } else if (e == "gt") {
        out += '>';
      } else if (e == "amp") {
        out += '&';
      } else if (e == "quot") {
        out += '"';
      } else if (e == "apos") {
        out += '\'';
      } else if (e.size() > 1 && e[0] == '#') {
        const bool hex = e[1] == 'x' || e[1] == 'X';
        append_utf8(out, std::strtoul(e.c_str() + (hex ? 2 : 1), nullptr, hex ? 16 : 10));
      } else {
        out += s_[i_++];
        continue;
      }
      i_ = semi + 1;
    }
  }
  XmlElement element(int depth) {
    if (depth > 1000) fail("elements nested too deeply");
    ++i_;  // '<'
    XmlElement e;
    const std::string tag = name();
    e.name = local(tag);
    for (;;) {
      spaces();
      if (i_ >= s_.size()) fail("unterminated tag <" + tag + ">");
      if (at("/>")) {
        i_ += 2;
        return e;
      }
      if (s_[i_] == '>') {
        ++i_;
        break;
      }
      std::string key = name();
      spaces();
      if (!at("=")) fail("attribute " + key + " without a value");
      ++i_;
      spaces();
      if (i_ >= s_.size() || (s_[i_] != '"' && s_[i_] != '\'')) fail("attribute " + key + ": expected a quote");
      const char quote = s_[i_++];
      const size_t end = s_.find(quote, i_);
      if (end == std::string::npos) fail("attribute " + key + ": no closing quote");
      std::string value;
      decode(end, value);
      i_ = end + 1;
      e.attributes.emplace_back(local(key), std::move(value));
    }
    for (;;) {
      if (i_ >= s_.size()) fail("<" + tag + "> is not closed");
      if (at("</")) {
        i_ += 2;
        if (name() != tag) fail("</...> does not close <" + tag + ">");
        spaces();
        if (!at(">")) fail("expected '>'");
        ++i_;
        return e;
      }
      if (at("<![CDATA[")) {
        i_ += 9;
        const size_t end = s_.find("]]>", i_);
        if (end == std::string::npos) fail("unterminated CDATA");
        e.text.append(s_, i_, end - i_);
        i_ = end + 3;
      } else if (at("<!--")) {
        skip_past("-->");
      } else if (at("<?")) {
        skip_past("?>");
      } else if (s_[i_] == '<') {
        e.children.push_back(element(depth + 1));
      } else {
        size_t end = s_.find('<', i_);
        if (end == std::string::npos) end = s_.size();
        decode(end, e.text);
      }
    }
  }
};

[[noreturn]] void fail(const std::string& what) { throw Error(what); }

std::vector<double> numbers(const std::string& text, const std::string& what) {
  std::vector<double> out;
  const char* p = text.c_str();
  for (;;) {
    while (*p && std::isspace(static_cast<unsigned char>(*p))) ++p;
    if (!*p) break;
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p) fail(what + ": not a number near '" + std::string(p).substr(0, 16) + "'");
    out.push_back(v);
    p = end;
  }
  return out;
}

// Integers as assimp reads indices: negative ones taken as 0.
std::vector<size_t> indices(const std::string& text, const std::string& what) {
  std::vector<size_t> out;
  const char* p = text.c_str();
  for (;;) {
    while (*p && std::isspace(static_cast<unsigned char>(*p))) ++p;
    if (!*p) break;
    char* end = nullptr;
    const long v = std::strtol(p, &end, 10);
    if (end == p) fail(what + ": not an integer near '" + std::string(p).substr(0, 16) + "'");
    out.push_back(static_cast<size_t>(std::max(0L, v)));
    p = end;
  }
  return out;
}

std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  return {std::istream_iterator<std::string>(in), std::istream_iterator<std::string>()};
}

// Elements by id, document-wide.
void index_ids(const XmlElement& e, std::map<std::string, const XmlElement*>& ids) {
  if (e.has("id")) ids.emplace(e.attribute("id"), &e);
  for (const XmlElement& c : e.children) index_ids(c, ids);
}

const XmlElement& by_url(const std::map<std::string, const XmlElement*>& ids, const std::string& url,
                         const std::string& what) {
  if (url.empty() || url[0] != '#') fail(what + ": '" + url + "' is not a local reference");
  const auto it = ids.find(url.substr(1));
  if (it == ids.end()) fail(what + ": no element with id '" + url.substr(1) + "'");
  return *it->second;
}

// A <source>'s values (floats or names) as its accessor reads them:
// `count` items of `stride` values from `offset`.
struct SourceData {
  std::vector<double> values;
  std::vector<std::string> names;
  size_t count = 0, stride = 1, offset = 0;
};

SourceData read_source(const XmlElement& source, const std::string& what) {
  SourceData d;
  if (const XmlElement* a = source.child("float_array")) {
    d.values = numbers(a->text, what);
  } else if (const XmlElement* n = source.child("Name_array")) {
    d.names = words(n->text);
  } else if (const XmlElement* r = source.child("IDREF_array")) {
    d.names = words(r->text);
  } else {
    fail(what + ": no float_array, Name_array or IDREF_array");
  }
  const XmlElement* tc = source.child("technique_common");
  const XmlElement* acc = tc ? tc->child("accessor") : nullptr;
  const size_t size = d.names.empty() ? d.values.size() : d.names.size();
  if (!acc) {
    d.count = size;
    return d;
  }
  d.count = std::strtoul(acc->attribute("count").c_str(), nullptr, 10);
  if (acc->has("stride")) d.stride = std::strtoul(acc->attribute("stride").c_str(), nullptr, 10);
  if (acc->has("offset")) d.offset = std::strtoul(acc->attribute("offset").c_str(), nullptr, 10);
  if (d.stride == 0) fail(what + ": accessor stride 0");
  if (d.count > 0 && d.offset + (d.count - 1) * d.stride >= size) fail(what + ": its accessor runs past the array");
  return d;
}

bool known_semantic(const std::string& s) {  // assimp's GetTypeForSemantic
  return s == "POSITION" || s == "TEXCOORD" || s == "UV" || s == "NORMAL" || s == "COLOR" || s == "VERTEX" ||
         s == "BINORMAL" || s == "TEXBINORMAL" || s == "TANGENT" || s == "TEXTANGENT";
}

// A skinned geometry: its <vertices> positions and, per primitive element
// that has faces, the <vertices> index of each corner in assimp's order.
struct Geometry {
  std::vector<double> positions;
  std::vector<std::vector<size_t>> corners;
};

Geometry read_geometry(const XmlElement& geometry, const std::map<std::string, const XmlElement*>& ids,
                       const std::string& what) {
  const XmlElement* mesh = geometry.child("mesh");
  if (!mesh) fail(what + ": no <mesh>");
  const XmlElement* vertices = mesh->child("vertices");
  if (!vertices) fail(what + ": no <vertices>");
  const std::string vertices_id = vertices->attribute("id");
  Geometry g;
  bool found = false;
  for (const XmlElement& in : vertices->children) {
    if (in.name != "input" || in.attribute("semantic") != "POSITION") continue;
    const SourceData p = read_source(by_url(ids, in.attribute("source"), what + " POSITION"), what + " positions");
    if (p.values.empty() || p.stride < 3) fail(what + ": positions are not xyz floats");
    for (size_t k = 0; k < p.count; ++k)
      for (int d = 0; d < 3; ++d) g.positions.push_back(p.values[p.offset + k * p.stride + d]);
    found = true;
    break;
  }
  if (!found) fail(what + ": <vertices> has no POSITION input");
  const size_t n = g.positions.size() / 3;

  static const std::set<std::string> kinds{"triangles", "lines",   "linestrips", "polygons",
                                           "polylist",  "trifans", "tristrips"};
  for (const XmlElement& prim : mesh->children) {
    if (!kinds.count(prim.name)) continue;
    const std::string pwhat = what + " <" + prim.name + ">";
    const size_t count = std::strtoul(prim.attribute("count").c_str(), nullptr, 10);
    size_t offsets = 1, vertex_offset = SIZE_MAX;
    for (const XmlElement& in : prim.children) {
      if (in.name != "input" || !known_semantic(in.attribute("semantic"))) continue;
      const size_t off = std::strtoul(in.attribute("offset").c_str(), nullptr, 10);
      offsets = std::max(offsets, off + 1);
      if (in.attribute("semantic") == "VERTEX") {
        if (in.attribute("source") != "#" + vertices_id) fail(pwhat + ": its VERTEX input is not the <vertices>");
        vertex_offset = off;
      }
    }
    if (vertex_offset == SIZE_MAX) fail(pwhat + ": no VERTEX input");
    std::vector<size_t> vcount;
    if (const XmlElement* vc = prim.child("vcount"); vc && count > 0) {
      vcount = indices(vc->text, pwhat + " <vcount>");
      if (vcount.size() < count) fail(pwhat + ": fewer <vcount> values than count");
      vcount.resize(count);
    }
    std::vector<size_t> corners;
    size_t faces = 0;
    for (const XmlElement& p : prim.children) {
      if (p.name != "p") continue;
      const std::vector<size_t> idx = count > 0 ? indices(p.text, pwhat + " <p>") : std::vector<size_t>{};
      const size_t points = idx.size() / offsets;
      size_t primitives = count;
      if (prim.name == "triangles" && idx.size() != 3 * count * offsets) fail(pwhat + ": <p> is not 3 x count");
      if (prim.name == "lines" && idx.size() != 2 * count * offsets) primitives = points / 2;
      if (prim.name == "polylist") {
        size_t total = 0;
        for (size_t v : vcount) total += v;
        if (idx.size() != total * offsets) fail(pwhat + ": <p> does not match <vcount>");
      }
      if (idx.size() % offsets != 0) fail(pwhat + ": <p> is not whole vertices");
      if (prim.name == "polygons" || prim.name == "trifans") primitives = 1;
      if (prim.name == "tristrips") primitives = points >= 2 ? points - 2 : 0;
      if (prim.name == "linestrips") primitives = points >= 1 ? points - 1 : 0;
      const auto corner = [&](size_t base) {
        if (base + vertex_offset >= idx.size()) fail(pwhat + ": <p> is too short");
        const size_t k = idx[base + vertex_offset];
        if (k >= n) fail(pwhat + ": vertex index " + std::to_string(k) + " of " + std::to_string(n));
        corners.push_back(k);
      };
      size_t start = 0;
      for (size_t f = 0; f < primitives; ++f) {
        if (prim.name == "lines") {
          for (size_t v = 0; v < 2; ++v) corner(f * offsets * 2 + v * offsets);
        } else if (prim.name == "triangles") {
          for (size_t v = 0; v < 3; ++v) corner(f * offsets * 3 + v * offsets);
        } else if (prim.name == "linestrips") {
          for (size_t v = 0; v < 2; ++v) corner(f * offsets + v * offsets);
        } else if (prim.name == "tristrips") {
          const size_t order[2][3] = {{0, 1, 2}, {1, 0, 2}};
          for (size_t v : order[f % 2]) corner(f * offsets + v * offsets);
        } else if (prim.name == "polylist") {
          for (size_t v = 0; v < vcount[f]; ++v) corner((start + v) * offsets);
          start += vcount[f];
        } else {  // polygons, trifans: the whole <p> is one face
          for (size_t v = 0; v < points; ++v) corner(v * offsets);
        }
      }
      faces += primitives;
    }
    if (faces > 0) g.corners.push_back(std::move(corners));
  }
  return g;
}

// The controller's raw weights per <vertices> entry, joints by the names the
// skin gives them.
std::vector<std::vector<std::pair<std::string, double>>> read_skin_weights(
    const XmlElement& skin, const std::map<std::string, const XmlElement*>& ids, const std::string& what) {
  const XmlElement* vw = skin.child("vertex_weights");
  if (!vw) fail(what + ": no <vertex_weights>");
  size_t offsets = 1, joint_offset = SIZE_MAX, weight_offset = SIZE_MAX;
  SourceData joints, weights;
  for (const XmlElement& in : vw->children) {
    if (in.name != "input") continue;
    const size_t off = std::strtoul(in.attribute("offset").c_str(), nullptr, 10);
    offsets = std::max(offsets, off + 1);
    if (in.attribute("semantic") == "JOINT") {
      joint_offset = off;
      joints = read_source(by_url(ids, in.attribute("source"), what + " JOINT"), what + " joints");
    } else if (in.attribute("semantic") == "WEIGHT") {
      weight_offset = off;
      weights = read_source(by_url(ids, in.attribute("source"), what + " WEIGHT"), what + " weights");
    }
  }
  if (joint_offset == SIZE_MAX || weight_offset == SIZE_MAX) fail(what + ": <vertex_weights> lacks JOINT or WEIGHT");
  const XmlElement* vc = vw->child("vcount");
  const XmlElement* v = vw->child("v");
  const std::vector<size_t> vcount = vc ? indices(vc->text, what + " <vcount>") : std::vector<size_t>{};
  const std::vector<size_t> pairs = v ? indices(v->text, what + " <v>") : std::vector<size_t>{};
  std::vector<std::vector<std::pair<std::string, double>>> rows(vcount.size());
  size_t at = 0;
  for (size_t k = 0; k < vcount.size(); ++k)
    for (size_t e = 0; e < vcount[k]; ++e, at += offsets) {
      if (at + offsets > pairs.size()) fail(what + ": <v> is shorter than <vcount> says");
      const size_t j = pairs[at + joint_offset], w = pairs[at + weight_offset];
      if (j >= joints.count || w >= weights.count || weights.values.empty() || joints.names.empty())
        fail(what + ": vertex " + std::to_string(k) + " names a joint or weight out of range");
      rows[k].emplace_back(joints.names[joints.offset + j * joints.stride],
                           weights.values[weights.offset + w * weights.stride]);
    }
  return rows;
}

// The name assimp gives the bone of skin joint `name`: the node whose name
// or id is `name` (pre-order), else whose sid is; that node's id (else sid).
std::string node_name_for_joint(const XmlElement& scenes, const std::string& name) {
  const XmlElement* found = nullptr;
  const std::function<void(const XmlElement&, bool)> visit = [&](const XmlElement& e, bool by_sid) {
    if (found) return;
    if (e.name == "node" &&
        (by_sid ? e.attribute("sid") == name : (e.attribute("name") == name || e.attribute("id") == name))) {
      found = &e;
      return;
    }
    for (const XmlElement& c : e.children) visit(c, by_sid);
  };
  visit(scenes, false);
  if (!found) visit(scenes, true);
  if (!found) return name;
  return found->has("id") && !found->attribute("id").empty() ? found->attribute("id") : found->attribute("sid");
}

bool near(double a, double b) { return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(b)); }

// A skin source's array size and accessor offset and stride, as assimp
// reads them (no check of the accessor's count against the array).
struct SkinArray {
  size_t size = 0, offset = 0, stride = 1;
};

bool skin_array(const std::map<std::string, const XmlElement*>& ids, const std::string& url, SkinArray& out) {
  if (url.empty() || url[0] != '#') return false;
  const auto it = ids.find(url.substr(1));
  if (it == ids.end()) return false;
  const XmlElement& source = *it->second;
  if (const XmlElement* a = source.child("float_array")) {
    try {
      out.size = numbers(a->text, "").size();
    } catch (const Error&) {
      return false;  // assimp reports it
    }
  } else if (const XmlElement* n = source.child("Name_array")) {
    out.size = words(n->text).size();
  } else if (const XmlElement* r = source.child("IDREF_array")) {
    out.size = words(r->text).size();
  } else {
    return false;
  }
  // assimp reads as many values as the array's count says, no more.
  for (const char* kind : {"float_array", "Name_array", "IDREF_array"})
    if (const XmlElement* a = source.child(kind); a && a->has("count"))
      out.size = std::min<size_t>(out.size, std::strtoul(a->attribute("count").c_str(), nullptr, 10));
  const XmlElement* tc = source.child("technique_common");
  if (const XmlElement* acc = tc ? tc->child("accessor") : nullptr) {
    if (acc->has("stride")) out.stride = std::strtoul(acc->attribute("stride").c_str(), nullptr, 10);
    if (acc->has("offset")) out.offset = std::strtoul(acc->attribute("offset").c_str(), nullptr, 10);
  }
  return true;
}

// The first <p>, <vcount> or <v> (under `e`) that is not integers only:
// "<p> in <geometry> 'id': not an integer near ...".
void check_index_lists(const XmlElement& e, const std::string& owner) {
  const std::string here = e.has("id") ? "<" + e.name + "> '" + e.attribute("id") + "'" : owner;
  for (const XmlElement& c : e.children) {
    if (c.name == "p" || c.name == "vcount" || c.name == "v") indices(c.text, "<" + c.name + "> in " + here);
    check_index_lists(c, here);
  }
}

}  // namespace

void check_collada_for_assimp(const std::string& path) {
  XmlElement root;
  std::map<std::string, const XmlElement*> ids;
  try {
    std::ifstream in(path, std::ios::binary);
    const std::string text(std::istreambuf_iterator<char>(in), {});
    root = XmlReader(text).document();
  } catch (const Error&) {
    return;  // not for this reader: assimp reports what it cannot read
  }
  index_ids(root, ids);
  try {
    check_index_lists(root, "<" + root.name + ">");
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  // Animation sources: assimp reads each accessor's items from the array
  // (as many values as its count says) and only asserts that they are there.
  if (const XmlElement* anims = root.child("library_animations")) {
    const std::function<void(const XmlElement&)> visit = [&](const XmlElement& e) {
      for (const XmlElement& c : e.children) {
        if (c.name == "source") {
          SkinArray a;
          const XmlElement* tc = c.child("technique_common");
          const XmlElement* acc = tc ? tc->child("accessor") : nullptr;
          if (acc && skin_array(ids, "#" + c.attribute("id"), a)) {
            const size_t count = std::strtoul(acc->attribute("count").c_str(), nullptr, 10);
            // Whole items: a param can be wider than one value (float4x4).
            const double need = double(a.offset) + double(count) * double(a.stride);
            if (need > double(a.size))
              throw Error(path + ": animation <source> '" + c.attribute("id") + "': its accessor reads " +
                          std::to_string(static_cast<unsigned long long>(need)) + " values of " +
                          std::to_string(a.size));
          }
        }
        visit(c);
      }
    };
    visit(*anims);
  }
  const XmlElement* lib = root.child("library_controllers");
  if (!lib) return;
  for (const XmlElement& ctrl : lib->children) {
    const XmlElement* skin = ctrl.name == "controller" ? ctrl.child("skin") : nullptr;
    const XmlElement* vw = skin ? skin->child("vertex_weights") : nullptr;
    if (!vw) continue;
    const std::string what = path + ": controller '" + ctrl.attribute("id") + "' <vertex_weights>";
    size_t offsets = 1, joint_offset = SIZE_MAX, weight_offset = SIZE_MAX;
    SkinArray joints, weights;
    bool arrays = true;
    for (const XmlElement& in : vw->children) {
      if (in.name != "input") continue;
      const size_t off = std::strtoul(in.attribute("offset").c_str(), nullptr, 10);
      offsets = std::max(offsets, off + 1);
      if (in.attribute("semantic") == "JOINT") {
        joint_offset = off;
        arrays = arrays && skin_array(ids, in.attribute("source"), joints);
      } else if (in.attribute("semantic") == "WEIGHT") {
        weight_offset = off;
        arrays = arrays && skin_array(ids, in.attribute("source"), weights);
      }
    }
    if (joint_offset == SIZE_MAX || weight_offset == SIZE_MAX || !arrays) continue;
    const XmlElement* vc = vw->child("vcount");
    const XmlElement* v = vw->child("v");
    std::vector<size_t> vcount, pairs;
    try {
      vcount = vc ? indices(vc->text, "<vcount>") : std::vector<size_t>{};
      pairs = v ? indices(v->text, "<v>") : std::vector<size_t>{};
    } catch (const Error& e) {
      throw Error(what + ": " + e.what());
    }
    const auto in_range = [](const SkinArray& a, size_t index) {
      return index <= (SIZE_MAX - a.offset) / std::max<size_t>(a.stride, 1) && a.offset + index * a.stride < a.size;
    };
    size_t at = 0;
    for (size_t k = 0; k < vcount.size(); ++k)
      for (size_t e = 0; e < vcount[k]; ++e, at += offsets) {
        if (at + offsets > pairs.size() || at + offsets < at)
          throw Error(what + ": <v> is shorter than <vcount> says (at vertex " + std::to_string(k) + ")");
        const size_t j = pairs[at + joint_offset], w = pairs[at + weight_offset];
        if (!in_range(joints, j))
          throw Error(what + ": vertex " + std::to_string(k) + " names joint " + std::to_string(j) + " of " +
                      std::to_string(joints.size));
        if (!in_range(weights, w))
          throw Error(what + ": vertex " + std::to_string(k) + " names weight " + std::to_string(w) + " of " +
                      std::to_string(weights.size));
      }
  }
}

std::string collapse_collada_corners(const std::string& path, const std::vector<ColladaCornerMesh>& meshes,
                                     const std::function<int32_t(const std::string&)>& joint, TriangleSurface& surface,
                                     WeightRows& rows) {
  try {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("cannot open the file");
    const std::string text(std::istreambuf_iterator<char>(in), {});
    const XmlElement root = XmlReader(text).document();
    std::map<std::string, const XmlElement*> ids;
    index_ids(root, ids);

    // The skin of each skinned geometry (the first controller that names it).
    std::map<std::string, const XmlElement*> skins;
    if (const XmlElement* lib = root.child("library_controllers"))
      for (const XmlElement& ctrl : lib->children)
        if (const XmlElement* skin = ctrl.name == "controller" ? ctrl.child("skin") : nullptr) {
          const std::string src = skin->attribute("source");
          if (!src.empty() && src[0] == '#') skins.emplace(src.substr(1), skin);
        }

    size_t total = 0;
    for (const ColladaCornerMesh& m : meshes) {
      if (m.first != static_cast<int32_t>(total)) fail("the meshes do not tile the surface");
      total += static_cast<size_t>(m.count);
    }
    if (total != surface.vertex_count() || rows.size() != total) fail("the meshes do not tile the surface");

    // Geometries in the order their meshes first appear.
    std::vector<std::string> order;
    std::map<std::string, Geometry> geometries;
    std::map<std::string, std::vector<bool>> used_primitive;
    for (const ColladaCornerMesh& m : meshes) {
      if (geometries.count(m.geometry)) continue;
      const std::string what = "geometry '" + m.geometry + "'";
      const auto it = ids.find(m.geometry);
      if (it == ids.end() || it->second->name != "geometry") fail("no <geometry> with id '" + m.geometry + "'");
      if (!skins.count(m.geometry)) fail(what + ": no controller's <skin> names it");
      geometries[m.geometry] = read_geometry(*it->second, ids, what);
      used_primitive[m.geometry].assign(geometries[m.geometry].corners.size(), false);
      order.push_back(m.geometry);
    }
    std::map<std::string, int32_t> base;
    size_t vertex_count = 0;
    for (const std::string& id : order) {
      base[id] = static_cast<int32_t>(vertex_count);
      vertex_count += geometries[id].positions.size() / 3;
    }

    // Each corner's new vertex, checked against the entry's position and the
    // weights of the entry's other corners.
    std::vector<int32_t> new_index(total, -1);
    std::vector<int32_t> first_corner(vertex_count, -1);
    const auto sorted_row = [&](size_t v) {
      auto r = rows[v];
      std::sort(r.begin(), r.end());
      return r;
    };
    for (const ColladaCornerMesh& m : meshes) {
      const Geometry& g = geometries[m.geometry];
      const std::string what = "geometry '" + m.geometry + "'";
      // The primitive element this mesh was made from: the first one not yet
      // taken with as many corners, at the same positions.
      int chosen = -1;
      for (size_t p = 0; p < g.corners.size() && chosen < 0; ++p) {
        if (used_primitive[m.geometry][p] || g.corners[p].size() != static_cast<size_t>(m.count)) continue;
        bool same = true;
        for (size_t c = 0; c < g.corners[p].size() && same; ++c)
          for (int d = 0; d < 3 && same; ++d)
            same = near(surface.positions(m.first + c, d), g.positions[3 * g.corners[p][c] + d]);
        if (same) chosen = static_cast<int>(p);
      }
      if (chosen < 0)
        fail(what + ": assimp's mesh of " + std::to_string(m.count) +
             " corners matches none of its primitive elements' corners");
      used_primitive[m.geometry][chosen] = true;
      for (size_t c = 0; c < g.corners[chosen].size(); ++c) {
        const int32_t v = base[m.geometry] + static_cast<int32_t>(g.corners[chosen][c]);
        const size_t corner = static_cast<size_t>(m.first) + c;
        new_index[corner] = v;
        if (first_corner[v] < 0) {
          first_corner[v] = static_cast<int32_t>(corner);
          continue;
        }
        const auto a = sorted_row(corner), b = sorted_row(static_cast<size_t>(first_corner[v]));
        bool same = a.size() == b.size();
        for (size_t k = 0; k < a.size() && same; ++k) same = a[k].first == b[k].first && near(a[k].second, b[k].second);
        if (!same)
          fail(what + ": the corners of vertex " + std::to_string(g.corners[chosen][c]) + " have different weights");
      }
    }

    // Loose entries: weights from the controller.
    TriangleSurface out;
    WeightRows out_rows(vertex_count);
    const XmlElement* scenes = root.child("library_visual_scenes");
    for (const std::string& id : order) {
      const Geometry& g = geometries[id];
      for (size_t k = 0; k + 2 < g.positions.size(); k += 3)
        out.positions.push_back({g.positions[k], g.positions[k + 1], g.positions[k + 2]});
      std::vector<std::vector<std::pair<std::string, double>>> skin_rows;
      bool skin_read = false;
      std::map<std::string, int32_t> joint_of;
      for (size_t k = 0; k < g.positions.size() / 3; ++k) {
        const int32_t v = base[id] + static_cast<int32_t>(k);
        if (first_corner[v] >= 0) {
          out_rows[v] = rows[first_corner[v]];
          continue;
        }
        if (!skin_read) {
          skin_rows = read_skin_weights(*skins.at(id), ids, "geometry '" + id + "' skin");
          skin_read = true;
        }
        if (k >= skin_rows.size()) continue;
        for (const auto& [name, w] : skin_rows[k]) {
          auto it = joint_of.find(name);
          if (it == joint_of.end())
            it = joint_of.emplace(name, joint(scenes ? node_name_for_joint(*scenes, name) : name)).first;
          if (it->second >= 0 && w > 0.0) out_rows[v].emplace_back(it->second, w);
        }
      }
    }
    out.triangles.reserve(surface.triangles.size());
    for (int32_t t : surface.triangles) {
      if (t < 0 || static_cast<size_t>(t) >= total || new_index[t] < 0) fail("a triangle corner outside the meshes");
      out.triangles.push_back(new_index[t]);
    }
    surface = std::move(out);
    rows = std::move(out_rows);
    return "";
  } catch (const Error& e) {
    return e.what();
  }
}

}  // namespace snh::detail
