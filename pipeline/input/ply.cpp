// The PLY reader: the header parsed line by line, elements before the vertices skipped, the
// vertices read into columns, every count checked against the bytes there are first.
//
// Written here rather than taken from a library: Debian 12 packages no PLY reader but
// OpenMesh's, which reads only the attributes it knows, returns a bool on a broken file (no
// vertex or property to name) and trusts the header's counts.
#include "pipeline/input/ply.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "pipeline/input/error.h"
#include "pipeline/input/limits.h"

namespace pleinair {

const PlyVertices::Column* PlyVertices::find(std::string_view name) const {
    for (const Column& c : columns)
        if (c.name == name) return &c;
    return nullptr;
}

namespace {

enum class Format { kAscii, kLittle, kBig };

struct Type {
    const char* name;
    const char* alias;
    int size;
    bool integer, is_signed;
};

constexpr Type kTypes[] = {
    {"char", "int8", 1, true, true},      {"uchar", "uint8", 1, true, false},
    {"short", "int16", 2, true, true},    {"ushort", "uint16", 2, true, false},
    {"int", "int32", 4, true, true},      {"uint", "uint32", 4, true, false},
    {"float", "float32", 4, false, true}, {"double", "float64", 8, false, true},
};

const Type* find_type(std::string_view name) {
    for (const Type& t : kTypes)
        if (name == t.name || name == t.alias) return &t;
    return nullptr;
}

struct Property {
    std::string name;
    const Type* type = nullptr;
    const Type* count_type = nullptr;  // lists only
    int column = -1;                   // vertex scalars: where its values go
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
};

// Splits a header line on spaces and tabs.
std::vector<std::string_view> words(std::string_view line) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        size_t j = i;
        while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
        if (j > i) out.push_back(line.substr(i, j - i));
        i = j;
    }
    return out;
}

std::string in_quotes(std::string_view s) {
    std::string q(1, '"');
    q.append(s.substr(0, s.size() > 40 ? 37 : s.size()));
    q.append(s.size() > 40 ? "...\"" : "\"");
    return q;
}

// A binary scalar of type t at p, in the file's byte order, as double.
double load(const unsigned char* p, const Type& t, bool big) {
    unsigned char b[8];
    std::memcpy(b, p, static_cast<size_t>(t.size));
    if (big != (std::endian::native == std::endian::big))
        for (int i = 0; i < t.size / 2; ++i) std::swap(b[i], b[t.size - 1 - i]);
    auto as = [&b]<class T>(T) {
        T v;
        std::memcpy(&v, b, sizeof v);
        return static_cast<double>(v);
    };
    if (!t.integer) return t.size == 4 ? as(float{}) : as(double{});
    switch (t.size) {
        case 1:
            return t.is_signed ? as(int8_t{}) : as(uint8_t{});
        case 2:
            return t.is_signed ? as(int16_t{}) : as(uint16_t{});
        default:
            return t.is_signed ? as(int32_t{}) : as(uint32_t{});
    }
}

class Parser {
  public:
    Parser(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) {}

    PlyVertices read() {
        read_header();
        PlyVertices out;
        for (const Element& e : elements_) {
            if (e.name == "vertex") {
                read_vertices(e, out);
                after_vertices(e);
                return out;
            }
            skip(e);
        }
        fail("", "no \"element vertex\" in the header");
    }

  private:
    std::string_view bytes_;
    const std::string& source_;
    size_t pos_ = 0;
    Format format_ = Format::kAscii;
    std::vector<Element> elements_;

    [[noreturn]] void fail(const std::string& where, const std::string& what) const {
        throw InputError(source_, where, what);
    }

    // The next header line (without its \n or \r\n); false at the end of the bytes.
    bool line(std::string_view& out) {
        if (pos_ >= bytes_.size()) return false;
        size_t end = bytes_.find('\n', pos_);
        if (end == std::string_view::npos) end = bytes_.size();
        out = bytes_.substr(pos_, end - pos_);
        if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
        // Past the newline, or at the end when the last line has none (fuzzing found a file
        // ending in "end_header" that put the data one byte past the end).
        pos_ = std::min(end + 1, bytes_.size());
        return true;
    }

    void read_header() {
        constexpr size_t kMaxHeaderLines = 4096;
        std::string_view l;
        if (!line(l) || l != "ply") fail("", "not a PLY file (the first line is not \"ply\")");
        bool have_format = false;
        for (size_t n = 2;; ++n) {
            const std::string at = "header line " + std::to_string(n);
            if (n > kMaxHeaderLines) fail(at, "no end_header in the first 4096 lines");
            if (!line(l)) fail(at, "the file ends inside its header (no end_header)");
            const auto w = words(l);
            if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
            if (w[0] == "end_header") break;
            if (w[0] == "format") {
                if (w.size() != 3 || w[2] != "1.0")
                    fail(at,
                         "expected \"format ascii|binary_little_endian|binary_big_endian "
                         "1.0\", got " +
                             in_quotes(l));
                if (w[1] == "ascii")
                    format_ = Format::kAscii;
                else if (w[1] == "binary_little_endian")
                    format_ = Format::kLittle;
                else if (w[1] == "binary_big_endian")
                    format_ = Format::kBig;
                else
                    fail(at, "unknown format " + in_quotes(w[1]));
                have_format = true;
            } else if (w[0] == "element") {
                uint64_t count = 0;
                if (w.size() != 3 ||
                    std::from_chars(w[2].data(), w[2].data() + w[2].size(), count).ptr !=
                        w[2].data() + w[2].size())
                    fail(at,
                         "expected \"element NAME COUNT\" with a whole number, got " + in_quotes(l));
                for (const Element& e : elements_)
                    if (e.name == w[1]) fail(at, "a second element " + in_quotes(w[1]));
                elements_.push_back({std::string(w[1]), count, {}});
            } else if (w[0] == "property") {
                if (elements_.empty()) fail(at, "a property before any element");
                Property p;
                if (w.size() == 5 && w[1] == "list") {
                    p.count_type = find_type(w[2]);
                    p.type = find_type(w[3]);
                    if (!p.count_type || !p.count_type->integer || !p.type)
                        fail(at,
                             "expected \"property list INTEGER_TYPE TYPE NAME\", got " + in_quotes(l));
                    p.name = w[4];
                } else if (w.size() == 3) {
                    p.type = find_type(w[1]);
                    if (!p.type) fail(at, "unknown property type " + in_quotes(w[1]));
                    p.name = w[2];
                } else {
                    fail(at, "expected \"property TYPE NAME\", got " + in_quotes(l));
                }
                for (const Property& q : elements_.back().properties)
                    if (q.name == p.name)
                        fail(at, "a second property " + in_quotes(p.name) + " in element " +
                                     in_quotes(elements_.back().name));
                elements_.back().properties.push_back(p);
            } else {
                fail(at, "unknown header keyword " + in_quotes(w[0]));
            }
        }
        if (!have_format) fail("", "the header has no format line");
    }

    // ASCII: the next whitespace-separated token, or empty at the end.
    std::string_view token() {
        while (pos_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[pos_])))
            ++pos_;
        const size_t start = pos_;
        while (pos_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[pos_])))
            ++pos_;
        return bytes_.substr(start, pos_ - start);
    }

    static std::string where(const Element& e, uint64_t i, const Property& p) {
        return e.name + " " + std::to_string(i) + " property " + p.name;
    }

    // One scalar of type t, checked: finite, and for integer types whole and in range.
    double scalar(const Element& e, uint64_t i, const Property& p, const Type& t) {
        double v;
        if (format_ == Format::kAscii) {
            const std::string_view tok = token();
            if (tok.empty())
                fail(where(e, i, p), "the file ends here: the header promises " +
                                         std::to_string(e.count) + " " + e.name +
                                         " elements (a truncated file, or a wrong count)");
            auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
            if (ec == std::errc::result_out_of_range && ptr == tok.data() + tok.size())
                fail(where(e, i, p), "not a finite number (" + in_quotes(tok) + " is out of range)");
            if (ec != std::errc() || ptr != tok.data() + tok.size())
                fail(where(e, i, p),
                     "expected a number (" + std::string(t.name) + "), got " + in_quotes(tok));
            if (t.integer) {
                const double lo = t.is_signed ? -std::ldexp(1.0, t.size * 8 - 1) : 0.0;
                const double hi = std::ldexp(1.0, t.size * 8 - (t.is_signed ? 1 : 0)) - 1;
                if (!(v == std::floor(v) && v >= lo && v <= hi))
                    fail(where(e, i, p), "expected a whole number that fits " +
                                             std::string(t.name) + ", got " + in_quotes(tok));
            }
        } else {
            if (bytes_.size() - pos_ < static_cast<size_t>(t.size))
                fail(where(e, i, p), "the file ends here: the header promises " +
                                         std::to_string(e.count) + " " + e.name +
                                         " elements (a truncated file, or a wrong count)");
            v = load(reinterpret_cast<const unsigned char*>(bytes_.data()) + pos_, t,
                     format_ == Format::kBig);
            pos_ += static_cast<size_t>(t.size);
        }
        if (!std::isfinite(v)) fail(where(e, i, p), "not a finite number");
        return v;
    }

    // The least bytes one element can take: what its header count is checked against.
    size_t min_bytes(const Element& e) const {
        size_t n = 0;
        for (const Property& p : e.properties)
            n += format_ == Format::kAscii
                     ? 2
                     : static_cast<size_t>((p.count_type ? p.count_type : p.type)->size);
        return n;
    }

    void check_count(const Element& e) const {
        const size_t left = bytes_.size() - std::min(pos_, bytes_.size());
        const size_t least = min_bytes(e);
        if (least > 0 && e.count > left / least)
            fail("element " + e.name,
                 "the header promises " + std::to_string(e.count) + " elements of at least " +
                     std::to_string(least) + " bytes, but only " + std::to_string(left) +
                     " bytes follow: " + e.name + " " + std::to_string(left / least) +
                     " is the first missing (a truncated file, or a wrong count)");
    }

    void element(const Element& e, uint64_t i, PlyVertices* out) {
        for (const Property& p : e.properties) {
            if (!p.count_type) {
                const double v = scalar(e, i, p, *p.type);
                if (out) out->columns[static_cast<size_t>(p.column)].values.push_back(v);
                continue;
            }
            const double n = scalar(e, i, p, *p.count_type);
            if (n < 0) fail(where(e, i, p), "a list of negative length");
            for (double k = 0; k < n; ++k) scalar(e, i, p, *p.type);
        }
    }

    void skip(const Element& e) {
        // An element of no properties takes no bytes, whatever its count (fuzzing found
        // 2.7e16 of them walked one by one).
        if (e.properties.empty()) return;
        check_count(e);
        bool fixed = format_ != Format::kAscii;
        for (const Property& p : e.properties) fixed = fixed && !p.count_type;
        if (fixed) {
            pos_ += static_cast<size_t>(e.count) * min_bytes(e);
            return;
        }
        for (uint64_t i = 0; i < e.count; ++i) element(e, i, nullptr);
    }

    void read_vertices(const Element& e, PlyVertices& out) {
        if (e.count > limits().particles)
            fail("element vertex", "the header promises " + std::to_string(e.count) +
                                       " vertices, over the limit of " +
                                       std::to_string(limits().particles) + "; " +
                                       how_to_raise("particles"));
        check_count(e);
        Element v = e;
        for (Property& p : v.properties) {
            if (p.count_type) continue;
            p.column = static_cast<int>(out.columns.size());
            out.columns.push_back({p.name, p.type->name, p.type->integer, {}});
            out.columns.back().values.reserve(static_cast<size_t>(e.count));
        }
        out.count = static_cast<size_t>(e.count);
        for (uint64_t i = 0; i < e.count; ++i) element(v, i, &out);
    }

    // With the vertices last, nothing may follow them: the count would be wrong.
    void after_vertices(const Element& e) {
        if (&e != &elements_.back()) return;
        if (format_ == Format::kAscii) {
            if (const std::string_view tok = token(); !tok.empty())
                fail("element vertex", "more values follow the " + std::to_string(e.count) +
                                           " vertices the header promises (a wrong count), "
                                           "starting with " +
                                           in_quotes(tok));
        } else if (pos_ < bytes_.size()) {
            fail("element vertex", std::to_string(bytes_.size() - pos_) + " bytes follow the " +
                                       std::to_string(e.count) +
                                       " vertices the header promises (a wrong count)");
        }
    }
};

}  // namespace

PlyVertices read_ply_vertices(std::string_view bytes, const std::string& source) {
    return Parser(bytes, source).read();
}

}  // namespace pleinair
