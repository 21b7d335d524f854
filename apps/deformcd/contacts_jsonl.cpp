#include "contacts_jsonl.h"

#include <array>
#include <charconv>

namespace deformcd::app {

namespace {

void append_float(std::string& out, float v) {
  std::array<char, 32> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  (void)ec;  // 32 characters hold any float
  out.append(buffer.data(), end);
}

void append_face(std::string& out, const ContactFace& f) {
  out += "{\"body\":" + std::to_string(f.body) + ",\"face\":" + std::to_string(f.face) +
         ",\"nodes\":[" + std::to_string(f.nodes[0]) + "," + std::to_string(f.nodes[1]) + "," +
         std::to_string(f.nodes[2]) + "]}";
}

void append_point(std::string& out, const glm::vec3& p) {
  out += '[';
  append_float(out, p.x);
  out += ',';
  append_float(out, p.y);
  out += ',';
  append_float(out, p.z);
  out += ']';
}

}  // namespace

std::string contacts_json_line(int frame, const std::vector<Contact>& contacts) {
  return "{\"frame\":" + std::to_string(frame) + ",\"contacts\":" + contacts_json_array(contacts) +
         "}\n";
}

std::string contacts_json_array(const std::vector<Contact>& contacts) {
  std::string out = "[";
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    if (i > 0) out += ',';
    out += "{\"a\":";
    append_face(out, c.a);
    out += ",\"b\":";
    append_face(out, c.b);
    if (c.coplanar) {
      out += ",\"coplanar\":true,\"segment\":null}";
      continue;
    }
    out += ",\"segment\":[";
    append_point(out, c.segment[0]);
    out += ',';
    append_point(out, c.segment[1]);
    out += "]}";
  }
  out += "]";
  return out;
}

}  // namespace deformcd::app
