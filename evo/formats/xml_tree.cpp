#include "evo/formats/xml_tree.hpp"

#include <cctype>
#include <stdexcept>

namespace bhm::evo {

const XmlNode* XmlNode::child(const std::string& n) const {
    for (const auto& c : children)
        if (c->name == n) return c.get();
    return nullptr;
}

std::vector<const XmlNode*> XmlNode::all(const std::string& n) const {
    std::vector<const XmlNode*> out;
    for (const auto& c : children)
        if (c->name == n) out.push_back(c.get());
    return out;
}

namespace {

class Parser {
  public:
    explicit Parser(const std::string& text) : s_(text) {}

    std::unique_ptr<XmlNode> document() {
        skip_misc();
        if (!starts("<")) fail("expected the root element");
        auto root = element(0);
        skip_misc();
        if (at_ < s_.size()) fail("text after the root element");
        return root;
    }

  private:
    const std::string& s_;
    std::size_t at_ = 0;

    [[noreturn]] void fail(const std::string& what) const {
        int line = 1;
        for (std::size_t i = 0; i < at_ && i < s_.size(); ++i)
            line += s_[i] == '\n' ? 1 : 0;
        throw std::runtime_error("line " + std::to_string(line) + ": " + what);
    }
    // Lines counted incrementally: elements only move forward.
    std::size_t counted_to_ = 0;
    int counted_lines_ = 1;
    int line_here() {
        for (; counted_to_ < at_; ++counted_to_)
            counted_lines_ += s_[counted_to_] == '\n' ? 1 : 0;
        return counted_lines_;
    }
    bool starts(const char* token) const {
        return s_.compare(at_, std::char_traits<char>::length(token), token) == 0;
    }
    void skip_space() {
        while (at_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[at_])))
            ++at_;
    }
    void skip_past(const char* end, const char* what) {
        const auto found = s_.find(end, at_);
        if (found == std::string::npos) fail(std::string("unterminated ") + what);
        at_ = found + std::char_traits<char>::length(end);
    }
    // Whitespace, comments, processing instructions and a DOCTYPE between elements.
    void skip_misc() {
        for (;;) {
            skip_space();
            if (starts("<?"))
                skip_past("?>", "processing instruction");
            else if (starts("<!--"))
                skip_past("-->", "comment");
            else if (starts("<!DOCTYPE"))
                skip_past(">", "DOCTYPE");
            else
                return;
        }
    }
    std::string name() {
        const std::size_t start = at_;
        while (at_ < s_.size() &&
               (std::isalnum(static_cast<unsigned char>(s_[at_])) || s_[at_] == '_' ||
                s_[at_] == '-' || s_[at_] == '.' || s_[at_] == ':'))
            ++at_;
        if (at_ == start) fail("expected a name");
        return s_.substr(start, at_ - start);
    }
    void append_utf8(std::string& out, unsigned long code) {
        if (code < 0x80) {
            out += static_cast<char>(code);
        } else if (code < 0x800) {
            out += static_cast<char>(0xc0 | (code >> 6));
            out += static_cast<char>(0x80 | (code & 0x3f));
        } else if (code < 0x10000) {
            out += static_cast<char>(0xe0 | (code >> 12));
            out += static_cast<char>(0x80 | ((code >> 6) & 0x3f));
            out += static_cast<char>(0x80 | (code & 0x3f));
        } else if (code < 0x110000) {
            out += static_cast<char>(0xf0 | (code >> 18));
            out += static_cast<char>(0x80 | ((code >> 12) & 0x3f));
            out += static_cast<char>(0x80 | ((code >> 6) & 0x3f));
            out += static_cast<char>(0x80 | (code & 0x3f));
        } else {
            fail("character reference out of range");
        }
    }
    void entity(std::string& out) {
        const auto end = s_.find(';', at_);
        if (end == std::string::npos || end - at_ > 12) fail("unterminated entity");
        const std::string e = s_.substr(at_ + 1, end - at_ - 1);
        if (e == "amp")
            out += '&';
        else if (e == "lt")
            out += '<';
        else if (e == "gt")
            out += '>';
        else if (e == "quot")
            out += '"';
        else if (e == "apos")
            out += '\'';
        else if (e.size() > 1 && e[0] == '#') {
            const bool hex = e[1] == 'x';
            const std::string digits = e.substr(hex ? 2 : 1);
            if (digits.empty()) fail("empty character reference");
            for (char c : digits)
                if (!(hex ? std::isxdigit(static_cast<unsigned char>(c))
                          : std::isdigit(static_cast<unsigned char>(c))))
                    fail("bad character reference &" + e + ";");
            append_utf8(out, std::stoul(digits, nullptr, hex ? 16 : 10));
        } else {
            fail("unknown entity &" + e + ";");
        }
        at_ = end + 1;
    }
    std::unique_ptr<XmlNode> element(int depth) {
        if (depth > 64) fail("elements nested too deeply");
        auto node = std::make_unique<XmlNode>();
        node->line = line_here();
        ++at_;  // '<'
        node->name = name();
        for (;;) {
            skip_space();
            if (starts("/>")) {
                at_ += 2;
                return node;
            }
            if (starts(">")) {
                ++at_;
                break;
            }
            const std::string key = name();
            skip_space();
            if (!starts("=")) fail("expected '=' after attribute " + key);
            ++at_;
            skip_space();
            if (at_ >= s_.size() || (s_[at_] != '"' && s_[at_] != '\'')) fail("expected a quote");
            const char quote = s_[at_++];
            std::string value;
            while (at_ < s_.size() && s_[at_] != quote) {
                if (s_[at_] == '<') fail("'<' in an attribute value");
                if (s_[at_] == '&')
                    entity(value);
                else
                    value += s_[at_++];
            }
            if (at_ >= s_.size()) fail("unterminated attribute value");
            ++at_;
            node->attributes[key] = value;
        }
        for (;;) {
            if (at_ >= s_.size()) fail("element <" + node->name + "> is not closed");
            if (starts("</")) {
                at_ += 2;
                const std::string closing = name();
                if (closing != node->name) fail("</" + closing + "> closes <" + node->name + ">");
                skip_space();
                if (!starts(">")) fail("expected '>'");
                ++at_;
                return node;
            }
            if (starts("<![CDATA[")) {
                const auto end = s_.find("]]>", at_);
                if (end == std::string::npos) fail("unterminated CDATA section");
                node->text += s_.substr(at_ + 9, end - at_ - 9);
                at_ = end + 3;
            } else if (starts("<!--")) {
                skip_past("-->", "comment");
            } else if (starts("<?")) {
                skip_past("?>", "processing instruction");
            } else if (starts("<")) {
                node->children.push_back(element(depth + 1));
            } else if (s_[at_] == '&') {
                entity(node->text);
            } else {
                node->text += s_[at_++];
            }
        }
    }
};

}  // namespace

std::unique_ptr<XmlNode> parse_xml(const std::string& text) {
    return Parser(text).document();
}

}  // namespace bhm::evo
