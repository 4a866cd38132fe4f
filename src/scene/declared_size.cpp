#include "scene/declared_size.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace shadowvol {
namespace {

constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();

// Saturating: a sum or product past 64 bits is more than any file holds.
std::uint64_t add(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r;
  return __builtin_add_overflow(a, b, &r) ? kMax : r;
}
std::uint64_t mul(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r;
  return __builtin_mul_overflow(a, b, &r) ? kMax : r;
}

// A count as readers take it: its leading digits, 0 where there are none (as strtoul reads);
// one too large for 64 bits reads as the most there is.
std::uint64_t parse_count(std::string_view text) {
  std::uint64_t out = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), out);
  if (error == std::errc::result_out_of_range) return kMax;
  return error == std::errc{} ? out : 0;
}

std::vector<std::string_view> tokens_of(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

// The least bytes of data a header declares, where its counts are (header_bytes, the header's
// own length), and the counts in words for the message.
struct Declared {
  std::uint64_t least_bytes = 0;
  std::uint64_t header_bytes = 0;
  std::string counts;
  bool ended = true;     // PLY: the header's end_header line was found
  std::string repeated;  // PLY: an element's name that the header defines twice
};

int ply_type_size(std::string_view type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
      type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

// ASCII data: every value a character at least, each followed by a separator but the last.
std::uint64_t ascii_bytes(std::uint64_t values) { return values == 0 ? 0 : mul(values, 2) - 1; }

bool ply_header(std::string_view text, Declared& out) {
  struct Element {
    std::string_view name;
    std::uint64_t count = 0;
    std::uint64_t values = 0, bytes = 0;  // least per element: ASCII values, binary bytes
  };
  std::vector<Element> elements;
  bool ascii = false;
  out.ended = false;
  std::size_t at = 0;
  // Lenient as readers are: a line it cannot make out adds nothing, but never hides the counts
  // of the lines it can; a header with no end_header where we looked ends there.
  for (int line_number = 0; at < text.size(); ++line_number) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const auto tokens = tokens_of(text.substr(at, end - at));
    at = std::min(end + 1, text.size());
    if (line_number == 0) {
      if (tokens.size() != 1 || tokens[0] != "ply") return false;
      continue;
    }
    if (tokens.empty()) continue;
    if (tokens[0] == "end_header") {
      out.ended = true;
      break;
    }
    if (tokens[0] == "format" && tokens.size() >= 2) {
      ascii = tokens[1] == "ascii";
    } else if (tokens[0] == "element" && tokens.size() >= 3) {
      for (const Element& e : elements)
        if (e.name == tokens[1] && out.repeated.empty()) out.repeated = std::string(tokens[1]);
      elements.push_back(Element{tokens[1], parse_count(tokens[2])});
    } else if (tokens[0] == "property" && !elements.empty() && tokens.size() >= 2) {
      Element& e = elements.back();
      const bool list = tokens[1] == "list" && tokens.size() >= 3;
      e.values += 1;  // a list holds its count at least
      // A type it cannot make out is still a byte at least (every PLY type is).
      e.bytes += static_cast<std::uint64_t>(std::max(1, ply_type_size(tokens[list ? 2 : 1])));
    }
  }
  std::uint64_t values = 0, bytes = 0;
  for (const Element& e : elements) {
    // Even an element without properties takes a byte (a line of its own in ASCII): readers
    // make an entry for each.
    values = add(values, mul(e.count, std::max<std::uint64_t>(1, e.values)));
    bytes = add(bytes, mul(e.count, std::max<std::uint64_t>(1, e.bytes)));
    std::string name(e.name);  // as a person can read it, whatever bytes the file holds
    for (char& c : name)
      if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
    out.counts +=
        (out.counts.empty() ? "element " : ", element ") + name + " " + std::to_string(e.count);
  }
  out.least_bytes = ascii ? ascii_bytes(values) : bytes;
  out.header_bytes = at;
  return true;
}

// OFF: [ST][C][N][4][n]OFF [dimension] vertices faces edges, then a line a vertex and a face.
bool off_header(std::string_view text, bool headerless, Declared& out) {
  std::vector<std::string_view> tokens;
  std::size_t at = 0;
  while (tokens.size() < 5 && at < text.size()) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    std::string_view line = text.substr(at, end - at);
    line = line.substr(0, line.find('#'));
    if (end == text.size()) return false;  // the header runs past what we read
    at = end + 1;
    for (std::string_view t : tokens_of(line)) tokens.push_back(t);
  }
  if (tokens.empty()) return false;
  std::string_view keyword = tokens[0];
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF") {
    // The keyword is optional (readers take the counts first in a file named .off).
    if (!headerless || tokens.size() < 2 || !std::isdigit(static_cast<unsigned char>(keyword[0])))
      return false;
    keyword = "OFF";
    tokens.insert(tokens.begin(), keyword);
  }
  std::uint64_t per_vertex = 3;
  std::string_view prefix = keyword.substr(0, keyword.size() - 3);
  const auto take = [&](std::string_view flag, std::uint64_t values) {
    if (!prefix.starts_with(flag)) return;
    prefix.remove_prefix(flag.size());
    per_vertex += values;
  };
  take("ST", 2);  // texture coordinates
  take("C", 1);   // a colour: one value at least
  take("N", 3);   // a normal
  take("4", 1);   // a homogeneous w
  const bool dimension = prefix == "n";
  if (!prefix.empty() && !dimension) return false;
  std::size_t next = 1;
  std::uint64_t dims = 3;
  if (dimension) dims = next < tokens.size() ? parse_count(tokens[next++]) : 0;
  if (dims > 3) return false;  // the reader refuses it
  per_vertex = per_vertex - 3 + dims;
  if (next + 1 >= tokens.size()) return false;
  const std::uint64_t vertices = parse_count(tokens[next]), faces = parse_count(tokens[next + 1]);
  // Each face line holds its vertex count at least.
  out.least_bytes = ascii_bytes(add(mul(vertices, per_vertex), faces));
  out.counts = std::to_string(vertices) + " vertices, " + std::to_string(faces) + " faces";
  out.header_bytes = 0;  // a few bytes: the whole file is the bound, and never too tight
  return true;
}

}  // namespace

Expected<void> check_declared_size(const std::filesystem::path& path, std::uintmax_t file_size) {
  constexpr std::size_t kHeaderBytes = 64 * 1024;
  std::ifstream in(path, std::ios::binary);
  std::string head(kHeaderBytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  Declared declared;
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool ply = ply_header(head, declared);
  if (!ply && !off_header(head, extension == ".off", declared)) return {};
  const std::uint64_t data_bytes =
      file_size > declared.header_bytes ? file_size - declared.header_bytes : 0;
  if (declared.least_bytes <= data_bytes) {
    // assimp (5.2) takes a header that defines an element twice into an inconsistent mesh, on
    // which its triangulation aborts.
    if (ply && !declared.repeated.empty()) {
      std::string name = declared.repeated;
      for (char& c : name)
        if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
      return make_error(path.string() + ": the PLY header defines the element '" + name +
                        "' twice");
    }
    // assimp (5.2) reads a PLY header without end_header forever.
    if (ply && !declared.ended)
      return make_error(path.string() + ": the PLY header has no end_header line" +
                        (head.size() < kHeaderBytes
                             ? std::string(" (is the file cut short?)")
                             : " in its first " + std::to_string(kHeaderBytes) + " bytes"));
    return {};
  }
  return make_error(path.string() + ": declares more data than the file holds (" + declared.counts +
                    ": at least " + std::to_string(declared.least_bytes) + " bytes, in a file of " +
                    std::to_string(file_size) +
                    " bytes); is the header corrupt or the file cut short?");
}

}  // namespace shadowvol
