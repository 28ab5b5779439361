#include "mesh/io/xml_element.h"

#include <gtest/gtest.h>

#include "support/status_message.h"

namespace kerf::mesh::internal {
namespace {

TEST(ParseXml, ElementsAttributesAndText) {
  const char* text =
      "<?xml version='1.0'?>\n<!-- c -->\n<a x=\"1\" y='two'>\n"
      "  <b>hello</b>\n  <c/>\n</a>\n";
  absl::StatusOr<XmlElement> root = ParseXml(text, "t.xml");
  ASSERT_TRUE(root.ok()) << root.status();
  EXPECT_EQ(root->name, "a");
  EXPECT_EQ(root->Attribute("y"), "two");
  EXPECT_FALSE(root->Attribute("z").has_value());
  ASSERT_EQ(root->children.size(), 2u);
  EXPECT_EQ(root->Child("b")->text, "hello");
  EXPECT_EQ(root->Child("c")->children.size(), 0u);
  EXPECT_EQ(root->Child("d"), nullptr);
}

TEST(ParseXml, Errors) {
  EXPECT_EQ(kerf::testing::StatusMessage(ParseXml("<a><b></a>", "t.xml")),
            "t.xml:1: expected </b>, found </a>");
  EXPECT_EQ(kerf::testing::StatusMessage(ParseXml("<a x=1/>", "t.xml")),
            "t.xml:1: expected a quoted value for attribute x");
  EXPECT_EQ(kerf::testing::StatusMessage(ParseXml("<a></a>\n<b/>", "t.xml")),
            "t.xml:2: expected the end of the document after the root element");
  EXPECT_EQ(kerf::testing::StatusMessage(ParseXml("<a><![CDATA[x]]></a>", "t.xml")),
            "t.xml:1: CDATA sections are not supported");
  EXPECT_EQ(ParseXml(std::string(100, '<'), "t.xml").status().code(),
            absl::StatusCode::kInvalidArgument);
  std::string deep;
  for (int i = 0; i < 40; ++i) deep += "<a>";
  EXPECT_EQ(kerf::testing::StatusMessage(ParseXml(deep, "t.xml")),
            "t.xml:1: XML nested too deeply");
}

}  // namespace
}  // namespace kerf::mesh::internal
