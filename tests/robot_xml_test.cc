// The XML check of robot files (formats/internal/robot_xml.h): every robot
// shipped with ccma passes with TinyXML's own element count; the markup on
// which TinyXML and TinyXML-2 split tokens differently is refused wherever it
// would hide elements (issue 34: `<?x >` then 100,000 nested elements
// crashed `ccma import`; an <sdf> that libsdformat read as a URDF); random
// documents of the accepted kind are counted as TinyXML counts them.
#include "formats/internal/robot_xml.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tinyxml.h>

#include "formats/model_loader.h"

namespace ccma {
namespace internal {
namespace robot_xml_test {

namespace fs = std::filesystem;

std::string Slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The message CheckRobotXml throws ("" if it accepts the text).
std::string Refusal(const std::string& text, const std::string& root = "robot") {
  try {
    CheckRobotXml(text, "r.urdf", root, "a URDF");
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

std::size_t TinyXmlElements(const TiXmlNode* node) {
  std::size_t n = node->ToElement() ? 1 : 0;
  for (const TiXmlNode* child = node->FirstChild(); child; child = child->NextSibling()) n += TinyXmlElements(child);
  return n;
}

TEST(RobotXml, EveryShippedRobotPassesWithTinyXmlsCount) {
  std::vector<fs::path> files;
  for (const fs::path& folder : {fs::path(CCMA_MODELS_DIR) / "robots", fs::path(CCMA_SOURCE_DIR) / "tests/data"}) {
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
      const std::string ext = entry.path().extension().string();
      if (ext == ".urdf" || ext == ".sdf") files.push_back(entry.path());
    }
  }
  ASSERT_GE(files.size(), 6u);
  for (const fs::path& file : files) {
    const std::string text = Slurp(file);
    const bool sdf = file.extension() == ".sdf";
    const RobotXmlSummary summary = CheckRobotXml(text, file.string(), sdf ? "sdf" : "robot", "a robot file");
    TiXmlDocument document;
    document.Parse(text.c_str(), nullptr, TIXML_ENCODING_UTF8);
    ASSERT_FALSE(document.Error()) << file;
    EXPECT_EQ(summary.elements, TinyXmlElements(&document)) << file;
    EXPECT_LT(summary.elements, kMaxRobotXmlElements / 10) << file;
  }
}

std::string Nested(int depth) {
  std::string text;
  for (int i = 0; i < depth; ++i) text += "<a>";
  for (int i = 0; i < depth; ++i) text += "</a>";
  return text;
}

// Markup TinyXML and TinyXML-2 end at different places, each followed by
// 100,000 nested elements: refused (or counted) before any parser recurses.
TEST(RobotXml, MarkupThatHidesElementsFromOneParserIsRefused) {
  const std::string deep = Nested(100000);
  const std::pair<std::string, std::string> cases[] = {
      {"<?x >" + deep + "<!-- ?> --><robot name=\"r\"/>", "r.urdf:1: expected the root element <robot>, found a "
                                                           "processing instruction"},
      {"<?xml version=\"1.0\"?><?x >" + deep + "?><robot/>", "r.urdf:1: expected the root element <robot>, found a "
                                                               "processing instruction"},
      {"<!x >" + deep + "<robot/>", "found '<!' markup"},
      {"<!DOCTYPE robot [<!ENTITY e \"x\">]>" + deep, "found a DOCTYPE"},
      {"<robot><?x >" + deep + "?></robot>", "r.urdf:1: a processing instruction ('<?') inside element 'robot' is "
                                              "not allowed"},
      {"<robot>< a>" + deep + "</robot>", "a '<' that does not start a tag inside element 'robot'"},
      {"<robot><!x " + deep + "></robot>", "'<!' markup inside element 'robot'"},
      {"<robot>\xF0<a>" + deep + "</robot>", "r.urdf:1: byte 0xf0 is not allowed"},
      {"<robot>\xEF\xBB\xBF<a>" + deep + "</robot>", "byte 0xef is not allowed"},
      {std::string("<robot>\0", 8) + deep + "</robot>", "byte 0x00 is not allowed"},
      {"<robot><a b=\"<\">" + deep + "</a></robot>", "'<' inside an attribute value"},
      {"<robot><a b=x>" + deep + "</a></robot>", "not valid XML: attribute values must be in quotes"},
      {"<robot>" + deep + "</robot>", "r.urdf:1: XML elements nested more than 100 deep"},
      {"<robot><!-- </a> -->" + deep + "</robot>", "nested more than 100 deep"},
      {"<robot><![CDATA[</a></a>]]>" + deep + "</robot>", "nested more than 100 deep"},
      {"<robot><a b=\"/>\" c='\"/>'>" + deep + "</a></robot>", "nested more than 100 deep"},
  };
  for (const auto& [text, needle] : cases) {
    const std::string message = Refusal(text);
    EXPECT_NE(message.find(needle), std::string::npos) << needle << "\n got: " << message.substr(0, 300);
    EXPECT_LT(message.size(), 400u);
  }
}

TEST(RobotXml, OneRootOfTheExpectedKindWithOnlyCommentsAfterIt) {
  EXPECT_EQ(Refusal("<?xml version=\"1.0\" encoding='UTF-8'?>\n<!-- c -->\n<robot name=\"r\"/>\n<!-- d -->\n"), "");
  EXPECT_EQ(Refusal("\xEF\xBB\xBF<robot/>"), "");  // a byte-order mark
  EXPECT_NE(Refusal("<?x ><sdf version=\"1.7\"/> <!-- ?> --><robot name=\"r\"/>", "sdf")
                .find("r.urdf:1: expected the root element <sdf>, found a processing instruction"),
            std::string::npos);
  EXPECT_NE(Refusal("<sdf version=\"1.7\"/>\n<robot name=\"r\"/>", "sdf")
                .find("r.urdf:2: found a '<' that does not start a tag after the root element <sdf>"),
            std::string::npos);
  EXPECT_NE(Refusal("<robot/>\ntext").find("r.urdf:2: found text after the root element <robot>"),
            std::string::npos);
  EXPECT_NE(Refusal("\n<sdf/>").find("r.urdf:2: not a URDF: its root element is 'sdf', not <robot>"),
            std::string::npos);
  EXPECT_NE(Refusal(" <?xml version=\"1.0\"?><robot/>").find("processing instruction"), std::string::npos);
  EXPECT_NE(Refusal("<robot>\n<a>\n</b>\n</robot>").find("r.urdf:3: not valid XML: closing tag 'b' does not match "
                                                           "element 'a'"),
            std::string::npos);
  EXPECT_NE(Refusal("<robot><a>").find("not valid XML: element 'a' is not closed"), std::string::npos);
  EXPECT_NE(Refusal("<robot><!-- x").find("not valid XML: comment not closed"), std::string::npos);
  EXPECT_NE(Refusal("").find("found the end of the file"), std::string::npos);
}

TEST(RobotXml, BoundsAreInclusiveAndNamesInMessagesAreQuoted) {
  EXPECT_EQ(Refusal("<robot>" + Nested(kMaxXmlNesting - 1) + "</robot>"), "");
  EXPECT_NE(Refusal("<robot>" + Nested(kMaxXmlNesting) + "</robot>").find("nested more than 100 deep"),
            std::string::npos);
  std::string many = "<robot>";
  for (std::size_t i = 1; i < kMaxRobotXmlElements; ++i) many += "<a/>";
  EXPECT_EQ(Refusal(many + "</robot>"), "");
  EXPECT_NE(Refusal(many + "<a/></robot>").find("more than 100000 elements"), std::string::npos);
  const std::string evil = "<robot><a\xc3\xa9x></a\x1b></robot>";
  EXPECT_NE(Refusal(evil).find("byte 0x1b"), std::string::npos);
  const std::string long_name = "<robot><" + std::string(1000000, 'n') + "></b></robot>";
  const std::string message = Refusal(long_name);
  EXPECT_NE(message.find("'nnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnn...' (1000000 bytes)"), std::string::npos);
  EXPECT_LT(message.size(), 200u);
}

// A random document built from what the check accepts (elements, attributes
// with quotes and '>' in values, comments, CDATA, text with entities and
// non-ASCII characters): accepted, with TinyXML's element count (seeded).
TEST(RobotXml, RandomAcceptedDocumentsCountAsTinyXmlCounts) {
  std::mt19937 random(34);
  const std::string texts[] = {"x", " 1 2 ", "&amp;", "&#x41;", "caf\xc3\xa9", "a>b", "\n"};
  const std::string values[] = {"\"v\"", "'v'", "\"a>b\"", "'\"'", "\"'\"", "\"&lt;\""};
  for (int trial = 0; trial < 200; ++trial) {
    std::string text = "<?xml version=\"1.0\"?>\n<robot>";
    std::vector<std::string> open = {"robot"};
    std::size_t elements = 1;
    while (!open.empty()) {
      const int pick = elements < 300 ? static_cast<int>(random() % 10) : 9;  // then close them all
      if (pick < 3 && open.size() < 20) {
        open.push_back("e" + std::to_string(pick) + (pick == 2 ? "-\xc3\xa9:x" : ""));
        text += "<" + open.back() + (pick == 1 ? " a=" + values[random() % 6] : "") + ">";
        ++elements;
      } else if (pick == 3) {
        text += "<f b=" + values[random() % 6] + " c = " + values[random() % 6] + "/>", ++elements;
      } else if (pick == 4) {
        text += "<!-- <g> ?> -->";
      } else if (pick == 5 && open.size() > 1) {
        text += "<![CDATA[<h>]]>";
      } else if (pick < 8) {
        text += texts[random() % 7];
      } else {
        text += "</" + open.back() + (pick == 8 ? " >" : ">");
        open.pop_back();
      }
    }
    RobotXmlSummary summary;
    ASSERT_NO_THROW(summary = CheckRobotXml(text, "r.urdf", "robot", "a URDF")) << text;
    TiXmlDocument document;
    document.Parse(text.c_str(), nullptr, TIXML_ENCODING_UTF8);
    ASSERT_FALSE(document.Error()) << text;
    EXPECT_EQ(summary.elements, elements) << text;
    EXPECT_EQ(summary.elements, TinyXmlElements(&document)) << text;
  }
}

}  // namespace
}  // namespace internal
}  // namespace ccma
