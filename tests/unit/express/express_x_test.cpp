// EXPRESS-X output: well-formed XML (checked with libxml2), the structure of the XSLT paper's
// cartesian_point example, every declaration and attribute of the input present, and the
// entity/attribute names of the real schemas recoverable from the XML alone.

#include "ncpost/express/express_x.hpp"

#include <gtest/gtest.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xpath.h>

#include <algorithm>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "corpus.hpp"
#include "test_support.hpp"

namespace ncpost::express {
namespace {

using Strings = std::vector<std::string>;

const xmlChar* xml_chars(const char* text) {
  return reinterpret_cast<const xmlChar*>(text);
}

std::string text_of(const xmlNode* node) {
  xmlChar* content = xmlNodeGetContent(node);
  std::string out = content != nullptr ? reinterpret_cast<const char*>(content) : "";
  xmlFree(content);
  return out;
}

std::string name_of(const xmlNode* node) {
  return reinterpret_cast<const char*>(node->name);
}

std::vector<const xmlNode*> children(const xmlNode* node, std::string_view name) {
  std::vector<const xmlNode*> out;
  for (const xmlNode* child = node->children; child != nullptr; child = child->next)
    if (child->type == XML_ELEMENT_NODE && name_of(child) == name) out.push_back(child);
  return out;
}

const xmlNode* child(const xmlNode* node, std::string_view name) {
  const auto found = children(node, name);
  return found.empty() ? nullptr : found.front();
}

// A parsed XML document with XPath helpers; `ok()` is false when the text is not well-formed.
class XmlDoc {
 public:
  explicit XmlDoc(const std::string& text)
      : doc_(xmlReadMemory(text.data(), static_cast<int>(text.size()), "express-x.xml", nullptr,
                           XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING),
             xmlFreeDoc) {}
  [[nodiscard]] bool ok() const { return doc_ != nullptr; }
  [[nodiscard]] const xmlNode* root() const { return xmlDocGetRootElement(doc_.get()); }

  // Text of every node the XPath expression selects.
  [[nodiscard]] Strings strings(const std::string& xpath) const {
    Strings out;
    for (const xmlNode* node : nodes(xpath)) out.push_back(text_of(node));
    return out;
  }
  [[nodiscard]] std::vector<const xmlNode*> nodes(const std::string& xpath) const {
    std::vector<const xmlNode*> out;
    std::unique_ptr<xmlXPathContext, decltype(&xmlXPathFreeContext)> context(
        xmlXPathNewContext(doc_.get()), xmlXPathFreeContext);
    std::unique_ptr<xmlXPathObject, decltype(&xmlXPathFreeObject)> result(
        xmlXPathEvalExpression(xml_chars(xpath.c_str()), context.get()), xmlXPathFreeObject);
    if (!result || result->nodesetval == nullptr) return out;
    for (int i = 0; i < result->nodesetval->nodeNr; ++i)
      out.push_back(result->nodesetval->nodeTab[i]);
    return out;
  }

 private:
  std::unique_ptr<xmlDoc, decltype(&xmlFreeDoc)> doc_;
};

constexpr std::string_view kGeometry = R"(
SCHEMA geometry;
  TYPE length_measure = REAL; END_TYPE;
  TYPE label = STRING; END_TYPE;
  ENTITY representation_item; name : label; END_ENTITY;
  ENTITY point SUBTYPE OF (representation_item); END_ENTITY;
  ENTITY cartesian_point
    SUBTYPE OF (point);
    coordinates : LIST [1:3] OF length_measure;
  END_ENTITY; -- 10303-42: geometry_schema
END_SCHEMA;
)";

TEST(express_x, CartesianPointHasTheStructureOfThePaper) {
  ASSERT_PARSES_CLEANLY(result, kGeometry);
  const XmlDoc xml(to_express_x(result.schemas));
  ASSERT_TRUE(xml.ok());
  const std::string entity = "//entity_decl[entity_id='cartesian_point']";
  EXPECT_EQ(xml.strings(entity + "/subtype_of/entity_ref"), (Strings{"point"}));
  EXPECT_EQ(xml.strings(entity + "/subtype_of/@express-production"),
            (Strings{"subtype_declaration"}));
  EXPECT_EQ(xml.strings(entity + "/subtype_of/entity_ref/@refType"),
            (Strings{"refid (entity_id)"}));
  const std::string attr = entity + "/explicit_attr_block/explicit_attr";
  EXPECT_EQ(xml.strings(attr + "/attribute_id"), (Strings{"coordinates"}));
  const std::string list = attr + "/base_type/list_type";
  EXPECT_EQ(xml.strings(list + "/bound_spec/lower_bound/integer_literal"), (Strings{"1"}));
  EXPECT_EQ(xml.strings(list + "/bound_spec/upper_bound/integer_literal"), (Strings{"3"}));
  EXPECT_EQ(xml.strings(list + "/bound_spec/lower_bound/@express-production"),
            (Strings{"bound_1"}));
  EXPECT_EQ(xml.strings(list + "/base_type/type_ref"), (Strings{"length_measure"}));
  EXPECT_EQ(xml.strings(list + "/base_type/type_ref/@refType"), (Strings{"refid (type_id)"}));
  EXPECT_EQ(xml.strings(entity + "/@express-production"), (Strings{"entity_decl"}));
  // Every element names its grammar production.
  EXPECT_TRUE(xml.nodes("//*[not(@express-production)]").empty());
}

TEST(express_x, TypeDeclarations) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA s;
    ENTITY circle; END_ENTITY;
    TYPE length_measure = REAL(6); END_TYPE;
    TYPE positive = length_measure; WHERE wr1 : SELF > 0; END_TYPE;
    TYPE shape = EXTENSIBLE SELECT (circle, length_measure); END_TYPE;
    TYPE more_shape = SELECT BASED_ON shape WITH (positive); END_TYPE;
    TYPE colour = ENUMERATION OF (red, green); END_TYPE;
    TYPE name = STRING(80) FIXED; END_TYPE;
    TYPE grid = ARRAY [0:?] OF OPTIONAL UNIQUE SET OF INTEGER; END_TYPE;
    END_SCHEMA;)");
  const XmlDoc xml(to_express_x(result.schemas));
  ASSERT_TRUE(xml.ok());
  EXPECT_EQ(xml.strings("//type_decl/type_id"), (Strings{"length_measure", "positive", "shape",
                                                         "more_shape", "colour", "name", "grid"}));
  EXPECT_EQ(xml.strings("//type_decl[type_id='length_measure']/underlying_type/real_type/"
                        "precision_spec/integer_literal"),
            (Strings{"6"}));
  EXPECT_EQ(xml.strings("//type_decl[type_id='positive']/underlying_type/type_ref"),
            (Strings{"length_measure"}));
  EXPECT_EQ(xml.strings("//type_decl[type_id='positive']/where_clause/domain_rule/rule_label_id"),
            (Strings{"wr1"}));
  EXPECT_EQ(xml.strings("//type_decl[type_id='positive']/where_clause/domain_rule/expression"),
            (Strings{"SELF > 0"}));
  const std::string shape = "//type_decl[type_id='shape']/underlying_type/select_type";
  EXPECT_EQ(xml.strings(shape + "/@extensible"), (Strings{"true"}));
  EXPECT_EQ(xml.strings(shape + "/select_list/entity_ref"), (Strings{"circle"}));
  EXPECT_EQ(xml.strings(shape + "/select_list/type_ref"), (Strings{"length_measure"}));
  EXPECT_EQ(xml.strings("//select_extension/type_ref"), (Strings{"shape"}));
  EXPECT_EQ(xml.strings("//select_extension/select_list/type_ref"), (Strings{"positive"}));
  EXPECT_EQ(xml.strings("//enumeration_type/enumeration_items/enumeration_id"),
            (Strings{"red", "green"}));
  EXPECT_EQ(xml.strings("//string_type/width_spec[@fixed='true']/integer_literal"),
            (Strings{"80"}));
  EXPECT_EQ(xml.strings("//array_type[@optional='true'][@unique='true']/bound_spec/"
                        "upper_bound/builtin_constant"),
            (Strings{"?"}));
  EXPECT_EQ(xml.nodes("//array_type/base_type/set_type/base_type/integer_type").size(), 1u);
}

TEST(express_x, EntityClauses) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA s;
    ENTITY shape ABSTRACT SUPERTYPE OF (ONEOF (circle, square));
      size : OPTIONAL REAL;
    END_ENTITY;
    ENTITY circle SUBTYPE OF (shape);
      SELF\shape.size RENAMED radius : REAL;
    DERIVE
      area : REAL := PI * radius ** 2;
    INVERSE
      users : SET [0:?] OF user FOR used;
    UNIQUE
      ur1 : radius, SELF\shape.size;
    WHERE
      wr1 : radius > 0;
    END_ENTITY;
    ENTITY square SUBTYPE OF (shape); END_ENTITY;
    ENTITY user; used : circle; END_ENTITY;
    END_SCHEMA;)");
  const XmlDoc xml(to_express_x(result.schemas));
  ASSERT_TRUE(xml.ok());
  EXPECT_EQ(xml.strings("//entity_decl[entity_id='shape']/abstract_supertype/subtype_constraint/"
                        "one_of/entity_ref"),
            (Strings{"circle", "square"}));
  EXPECT_EQ(xml.strings("//entity_decl[entity_id='shape']//explicit_attr/@optional"),
            (Strings{"true"}));
  const std::string circle = "//entity_decl[entity_id='circle']";
  const std::string redeclared = circle + "/explicit_attr_block/explicit_attr/redeclared_attribute";
  EXPECT_EQ(xml.strings(redeclared + "/qualified_attribute/entity_ref"), (Strings{"shape"}));
  EXPECT_EQ(xml.strings(redeclared + "/qualified_attribute/attribute_ref"), (Strings{"size"}));
  EXPECT_EQ(xml.strings(redeclared + "/rename_id"), (Strings{"radius"}));
  EXPECT_EQ(xml.strings(circle + "/derive_clause/derived_attr/attribute_id"), (Strings{"area"}));
  EXPECT_EQ(xml.strings(circle + "/derive_clause/derived_attr/expression"),
            (Strings{"PI * radius ** 2"}));
  EXPECT_EQ(xml.strings(circle + "/inverse_clause/inverse_attr/attribute_id"), (Strings{"users"}));
  EXPECT_EQ(xml.strings(circle + "/inverse_clause/inverse_attr/entity_ref"), (Strings{"user"}));
  EXPECT_EQ(xml.strings(circle + "/inverse_clause/inverse_attr/attribute_ref"), (Strings{"used"}));
  EXPECT_EQ(xml.strings(circle + "/inverse_clause/inverse_attr/set_type/bound_spec/lower_bound/*"),
            (Strings{"0"}));
  EXPECT_EQ(xml.strings(circle + "/unique_clause/unique_rule/rule_label_id"), (Strings{"ur1"}));
  EXPECT_EQ(xml.strings(circle + "/unique_clause/unique_rule/referenced_attribute//attribute_ref"),
            (Strings{"radius", "size"}));
  EXPECT_EQ(xml.strings(circle + "/where_clause/domain_rule/expression"), (Strings{"radius > 0"}));
  // Children in the order of the DTD in the paper.
  Strings order;
  for (const xmlNode* node : xml.nodes(circle + "/*")) order.push_back(name_of(node));
  EXPECT_EQ(order, (Strings{"entity_id", "subtype_of", "explicit_attr_block", "derive_clause",
                            "inverse_clause", "unique_clause", "where_clause"}));
}

TEST(express_x, TextIsEscapedAndAlwaysWellFormed) {
  // A string literal with markup characters, a lone Latin-1 byte and a control character.
  const std::string source =
      "SCHEMA s; ENTITY e; a : STRING; WHERE wr1 : a <> '<x & \"y\">' + '\xE9\x01'; "
      "END_ENTITY; END_SCHEMA;";
  ASSERT_PARSES_CLEANLY(result, source);
  const std::string text = to_express_x(result.schemas);
  const XmlDoc xml(text);
  ASSERT_TRUE(xml.ok()) << text;
  EXPECT_EQ(xml.strings("//domain_rule/expression"),
            (Strings{"a <> '<x & \"y\">' + '\xEF\xBF\xBD\xEF\xBF\xBD'"}));
  EXPECT_NE(text.find("&lt;x &amp;"), std::string::npos);
}

TEST(express_x, StreamAndStringFormsAreIdentical) {
  ASSERT_PARSES_CLEANLY(result, kGeometry);
  std::ostringstream stream;
  write_express_x(result.schemas, stream);
  EXPECT_EQ(stream.str(), to_express_x(result.schemas));
  EXPECT_EQ(stream.str().rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", 0), 0u);
}

// "entity.kind.name" for every attribute of every entity, from the model...
Strings declared_names(const SchemaSet& set) {
  Strings out;
  for (const Schema& schema : set.schemas()) {
    for (const Entity& e : schema.entities) {
      out.push_back(e.name);
      for (const auto& a : e.explicit_attributes) out.push_back(e.name + ".explicit." + a.name);
      for (const auto& a : e.derived_attributes) out.push_back(e.name + ".derived." + a.name);
      for (const auto& a : e.inverse_attributes) out.push_back(e.name + ".inverse." + a.name);
    }
    for (const TypeDecl& t : schema.types) out.push_back("type " + t.name);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// ... and the same, read back from the EXPRESS-X document alone.
std::string attribute_name(const xmlNode* attr) {
  if (const xmlNode* id = child(attr, "attribute_id")) return text_of(id);
  const xmlNode* redeclared = child(attr, "redeclared_attribute");
  if (redeclared == nullptr) return "?";
  if (const xmlNode* rename = child(redeclared, "rename_id")) return text_of(rename);
  return text_of(child(child(redeclared, "qualified_attribute"), "attribute_ref"));
}

Strings names_in_xml(const XmlDoc& xml) {
  Strings out;
  for (const xmlNode* decl : xml.nodes("//entity_decl")) {
    const std::string entity = text_of(child(decl, "entity_id"));
    out.push_back(entity);
    const auto add_all = [&](const char* block, const char* item, const char* kind) {
      if (const xmlNode* clause = child(decl, block))
        for (const xmlNode* attr : children(clause, item))
          out.push_back(entity + "." + kind + "." + attribute_name(attr));
    };
    add_all("explicit_attr_block", "explicit_attr", "explicit");
    add_all("derive_clause", "derived_attr", "derived");
    add_all("inverse_clause", "inverse_attr", "inverse");
  }
  for (const std::string& type : xml.strings("//type_decl/type_id")) out.push_back("type " + type);
  std::sort(out.begin(), out.end());
  return out;
}

TEST(express_x, CombinedIso14649SchemaRoundTripsItsNames) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const ParseResult result = parse_express(::ncpost::test::read_file(
      corpus / "express/michaloski_STEPNCpp_combined_schema_14649-10-11-12-111-121.exp"));
  ASSERT_TRUE(result.ok()) << test::describe(result.diagnostics);
  const XmlDoc xml(to_express_x(result.schemas));
  ASSERT_TRUE(xml.ok());
  const Strings expected = declared_names(result.schemas);
  ASSERT_GT(expected.size(), 1400u);  // 495 entities, 73 types and their attributes
  EXPECT_EQ(names_in_xml(xml), expected);
  // Spot check against the source text, independent of the model.
  EXPECT_EQ(xml.strings("//entity_decl[entity_id='machining_workingstep']//attribute_id"),
            (Strings{"its_feature", "its_operation", "its_effect"}));
}

TEST(express_x, EveryCorpusSchemaIsWellFormedAndComplete) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  std::size_t files = 0;
  for (const char* folder : {"express", "p21-syntax"}) {
    for (const auto& entry : std::filesystem::directory_iterator(corpus / folder)) {
      if (entry.path().extension() != ".exp") continue;
      ++files;
      const ParseResult result = parse_express(::ncpost::test::read_file(entry.path()));
      ASSERT_TRUE(result.ok()) << entry.path();
      const std::string text = to_express_x(result.schemas);
      const XmlDoc xml(text);
      ASSERT_TRUE(xml.ok()) << entry.path();
      EXPECT_EQ(names_in_xml(xml), declared_names(result.schemas)) << entry.path();
      EXPECT_TRUE(xml.nodes("//*[not(@express-production)]").empty()) << entry.path();
    }
  }
  EXPECT_GE(files, 6u);
}

}  // namespace
}  // namespace ncpost::express
