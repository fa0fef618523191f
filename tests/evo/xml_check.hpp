#pragma once
// A tiny XML well-formedness checker and tree reader for tests: prolog, comments, CDATA,
// attributes, the five predefined entities and numeric character references, matching tags,
// exactly one root element. Enough to prove a VXA file parses as XML; not a general parser.
#include <cctype>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace bhm::test {

struct XmlElement {
    std::string name;
    std::map<std::string, std::string> attributes;
    std::string text;  //!< character data directly inside, CDATA included, entities decoded
    std::vector<std::unique_ptr<XmlElement>> children;
    const XmlElement* child(const std::string& n) const {
        for (const auto& c : children)
            if (c->name == n) return c.get();
        return nullptr;
    }
    std::vector<const XmlElement*> all(const std::string& n) const {
        std::vector<const XmlElement*> out;
        for (const auto& c : children)
            if (c->name == n) out.push_back(c.get());
        return out;
    }
};

class XmlReader {
  public:
    //! Throws std::runtime_error with the offset of the first problem.
    static std::unique_ptr<XmlElement> parse(const std::string& text) {
        XmlReader r(text);
        return r.document();
    }

  private:
    explicit XmlReader(const std::string& t) : s_(t) {}
    [[noreturn]] void fail(const std::string& what) const {
        throw std::runtime_error("XML error at offset " + std::to_string(i_) + ": " + what);
    }
    bool starts(const char* p) const {
        return s_.compare(i_, std::char_traits<char>::length(p), p) == 0;
    }
    void skip_space() {
        while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_])))
            ++i_;
    }
    void skip_past(const char* end) {
        const auto at = s_.find(end, i_);
        if (at == std::string::npos) fail(std::string("missing ") + end);
        i_ = at + std::char_traits<char>::length(end);
    }
    void comment() {  // "--" may not appear inside, nor '-' right before the closing "-->"
        const auto end = s_.find("-->", i_ + 4);
        if (end == std::string::npos) fail("unterminated comment");
        const std::string body = s_.substr(i_ + 4, end - i_ - 4);
        if (body.find("--") != std::string::npos || (!body.empty() && body.back() == '-'))
            fail("'--' inside a comment");
        i_ = end + 3;
    }
    void skip_misc() {  // whitespace, comments, processing instructions
        for (;;) {
            skip_space();
            if (starts("<!--"))
                comment();
            else if (starts("<?"))
                skip_past("?>");
            else
                return;
        }
    }
    static bool name_char(char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' ||
               c == ':';
    }
    std::string name() {
        const std::size_t start = i_;
        if (i_ >= s_.size() || !(std::isalpha(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_'))
            fail("expected a name");
        while (i_ < s_.size() && name_char(s_[i_]))
            ++i_;
        return s_.substr(start, i_ - start);
    }
    std::string decode(const std::string& raw) {
        std::string out;
        for (std::size_t k = 0; k < raw.size(); ++k) {
            if (raw[k] == '<') fail("'<' in character data");
            if (raw[k] != '&') {
                out += raw[k];
                continue;
            }
            const auto semi = raw.find(';', k);
            if (semi == std::string::npos) fail("unterminated entity");
            const std::string entity = raw.substr(k + 1, semi - k - 1);
            static const std::map<std::string, char> named = {
                {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
            if (auto it = named.find(entity); it != named.end())
                out += it->second;
            else if (entity.size() > 1 && entity[0] == '#')
                out += '?';
            else
                fail("unknown entity &" + entity + ";");
            k = semi;
        }
        return out;
    }
    std::unique_ptr<XmlElement> element() {
        if (!starts("<")) fail("expected '<'");
        ++i_;
        auto e = std::make_unique<XmlElement>();
        e->name = name();
        for (;;) {
            skip_space();
            if (starts("/>")) {
                i_ += 2;
                return e;
            }
            if (starts(">")) {
                ++i_;
                break;
            }
            const std::string key = name();
            skip_space();
            if (!starts("=")) fail("expected '=' after attribute " + key);
            ++i_;
            skip_space();
            if (i_ >= s_.size() || (s_[i_] != '"' && s_[i_] != '\''))
                fail("expected a quoted value");
            const char quote = s_[i_++];
            const auto end = s_.find(quote, i_);
            if (end == std::string::npos) fail("unterminated attribute value");
            if (e->attributes.count(key)) fail("duplicate attribute " + key);
            e->attributes[key] = decode(s_.substr(i_, end - i_));
            i_ = end + 1;
        }
        for (;;) {
            if (i_ >= s_.size()) fail("missing </" + e->name + ">");
            if (starts("</")) {
                i_ += 2;
                if (name() != e->name) fail("mismatched closing tag for <" + e->name + ">");
                skip_space();
                if (!starts(">")) fail("expected '>'");
                ++i_;
                return e;
            }
            if (starts("<!--"))
                comment();
            else if (starts("<![CDATA[")) {
                i_ += 9;
                const auto end = s_.find("]]>", i_);
                if (end == std::string::npos) fail("unterminated CDATA");
                e->text += s_.substr(i_, end - i_);
                i_ = end + 3;
            } else if (starts("<?"))
                skip_past("?>");
            else if (starts("<"))
                e->children.push_back(element());
            else {
                const auto end = s_.find('<', i_);
                if (end == std::string::npos) fail("text after the last tag");
                e->text += decode(s_.substr(i_, end - i_));
                i_ = end;
            }
        }
    }
    std::unique_ptr<XmlElement> document() {
        skip_misc();
        auto root = element();
        skip_misc();
        if (i_ != s_.size()) fail("content after the root element");
        return root;
    }
    const std::string& s_;
    std::size_t i_ = 0;
};

}  // namespace bhm::test
