#pragma once
// A small XML reader for the files we import (VoxCAD VXA/VXC): elements, attributes, character
// data with the five predefined entities and numeric references, CDATA, comments, processing
// instructions and a DOCTYPE line skipped. No namespaces, no DTD entities. Errors name the line.
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace bhm::evo {

struct XmlNode {
    std::string name;
    std::map<std::string, std::string> attributes;
    std::string text;  //!< character data directly inside (CDATA included), entities decoded
    int line = 0;      //!< where the element starts, 1-based
    std::vector<std::unique_ptr<XmlNode>> children;

    const XmlNode* child(const std::string& n) const;  //!< first child of that name or nullptr
    std::vector<const XmlNode*> all(const std::string& n) const;
};

//! Parses one document; throws std::runtime_error "line N: what" on malformed input.
std::unique_ptr<XmlNode> parse_xml(const std::string& text);

}  // namespace bhm::evo
