// Flattened attribute lists in ISO 10303-21 order: supertypes first, depth-first left-to-right
// over SUBTYPE OF, each inherited attribute once, redeclarations in place, DERIVE
// redeclarations flagged (an instance has `*` there).

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "test_support.hpp"

namespace ncpost::express {
namespace {

using Strings = std::vector<std::string>;

constexpr std::string_view kFamily = R"(
SCHEMA family;
  ENTITY root;            id : STRING;                          END_ENTITY;
  ENTITY left  SUBTYPE OF (root); l1 : INTEGER; l2 : OPTIONAL REAL; END_ENTITY;
  ENTITY right SUBTYPE OF (root); r1 : INTEGER;                 END_ENTITY;
  ENTITY other;           o1 : BOOLEAN;                         END_ENTITY;
  -- root is reached through left and through right: its attribute comes once, first.
  ENTITY diamond  SUBTYPE OF (left, right, other); d1 : STRING;  END_ENTITY;
  ENTITY reversed SUBTYPE OF (other, right, left); d2 : STRING;  END_ENTITY;
  ENTITY grandchild SUBTYPE OF (diamond); g1 : LOGICAL;          END_ENTITY;

  ENTITY point; x, y : REAL; END_ENTITY;
  ENTITY on_x_axis SUBTYPE OF (point);
  DERIVE
    SELF\point.y : REAL := 0.0;
  END_ENTITY;
  ENTITY labelled_on_x_axis SUBTYPE OF (on_x_axis); label : STRING; END_ENTITY;

  ENTITY shape; size : NUMBER; caption : OPTIONAL STRING; END_ENTITY;
  ENTITY square SUBTYPE OF (shape);
    SELF\shape.size : INTEGER;
    extra : REAL;
    SELF\shape.caption RENAMED title : STRING;
  END_ENTITY;

  ENTITY base2; a : REAL; b : REAL; END_ENTITY;
  ENTITY derives_b SUBTYPE OF (base2); DERIVE SELF\base2.b : REAL := a * 2.0; END_ENTITY;
  ENTITY plain SUBTYPE OF (base2); c : INTEGER; END_ENTITY;
  ENTITY both SUBTYPE OF (plain, derives_b); END_ENTITY;
END_SCHEMA;
)";

class express_flatten : public ::testing::Test {
 protected:
  void SetUp() override {
    result_ = parse_express(kFamily);
    ASSERT_TRUE(result_.diagnostics.empty()) << test::describe(result_.diagnostics);
  }
  const Entity& entity(std::string_view name) {
    const Entity* e = result_.schemas.find_entity(name);
    EXPECT_NE(e, nullptr) << name;
    return *e;
  }
  std::vector<bool> derived(std::string_view name) {
    std::vector<bool> out;
    for (const auto& a : entity(name).attributes) out.push_back(a.derived_redeclared);
    return out;
  }
  ParseResult result_;
};

TEST_F(express_flatten, SingleInheritanceSupertypeAttributesFirst) {
  EXPECT_EQ(test::attribute_names(entity("left")), (Strings{"id", "l1", "l2"}));
  EXPECT_EQ(test::owners(entity("left")), (Strings{"root", "left", "left"}));
  EXPECT_TRUE(entity("left").attributes[2].optional);
}

TEST_F(express_flatten, MultipleInheritanceDepthFirstLeftToRightEachAttributeOnce) {
  EXPECT_EQ(test::attribute_names(entity("diamond")),
            (Strings{"id", "l1", "l2", "r1", "o1", "d1"}));
  EXPECT_EQ(test::attribute_names(entity("reversed")),
            (Strings{"o1", "id", "r1", "l1", "l2", "d2"}));
  EXPECT_EQ(test::attribute_names(entity("grandchild")),
            (Strings{"id", "l1", "l2", "r1", "o1", "d1", "g1"}));
  EXPECT_EQ(entity("diamond").attribute_index("R1"), 3u);
  EXPECT_FALSE(entity("diamond").attribute_index("g1").has_value());
}

TEST_F(express_flatten, AncestorsSubtypesAndIsSubtypeOf) {
  const SchemaSet& set = result_.schemas;
  std::vector<std::string> ancestors;
  for (const DeclRef ref : entity("diamond").ancestors) ancestors.emplace_back(set.name_of(ref));
  EXPECT_EQ(ancestors, (Strings{"root", "left", "right", "other"}));
  std::vector<std::string> subtypes;
  for (const DeclRef ref : entity("root").subtypes) subtypes.emplace_back(set.name_of(ref));
  EXPECT_EQ(subtypes, (Strings{"left", "right"}));

  EXPECT_TRUE(set.is_subtype_of("grandchild", "ROOT"));
  EXPECT_TRUE(set.is_subtype_of("diamond", "other"));
  EXPECT_TRUE(set.is_subtype_of("diamond", "diamond"));
  EXPECT_FALSE(set.is_subtype_of("root", "diamond"));
  EXPECT_FALSE(set.is_subtype_of("left", "right"));
  EXPECT_FALSE(set.is_subtype_of("nothing", "root"));
}

TEST_F(express_flatten, DeriveRedeclarationKeepsThePositionAndIsFlagged) {
  EXPECT_EQ(test::attribute_names(entity("on_x_axis")), (Strings{"x", "y"}));
  EXPECT_EQ(derived("on_x_axis"), (std::vector<bool>{false, true}));
  const FlatAttribute& y = entity("on_x_axis").attributes[1];
  EXPECT_EQ(y.owner, "point");
  EXPECT_EQ(y.redeclared_by, "on_x_axis");
  // The supertype itself is unchanged, and subtypes of the redeclaring entity inherit the flag.
  EXPECT_EQ(derived("point"), (std::vector<bool>{false, false}));
  EXPECT_EQ(test::attribute_names(entity("labelled_on_x_axis")), (Strings{"x", "y", "label"}));
  EXPECT_EQ(derived("labelled_on_x_axis"), (std::vector<bool>{false, true, false}));
}

TEST_F(express_flatten, ExplicitRedeclarationNarrowsTheTypeInPlace) {
  const Entity& square = entity("square");
  EXPECT_EQ(test::attribute_names(square), (Strings{"size", "title", "extra"}));
  EXPECT_EQ(square.attributes[0].type.kind, TypeKind::Integer);
  EXPECT_EQ(square.attributes[0].owner, "shape");
  EXPECT_EQ(square.attributes[0].redeclared_by, "square");
  EXPECT_FALSE(square.attributes[0].derived_redeclared);
  // RENAMED gives the position a new name; the redeclaration drops OPTIONAL.
  EXPECT_EQ(square.attributes[1].declared_name, "caption");
  EXPECT_FALSE(square.attributes[1].optional);
  EXPECT_EQ(entity("shape").attributes[0].type.kind, TypeKind::Number);
  EXPECT_TRUE(entity("shape").attributes[1].optional);
}

TEST_F(express_flatten, DeriveRedeclarationOnOneBranchOfADiamondApplies) {
  EXPECT_EQ(test::attribute_names(entity("both")), (Strings{"a", "b", "c"}));
  EXPECT_EQ(derived("both"), (std::vector<bool>{false, true, false}));
  EXPECT_EQ(derived("plain"), (std::vector<bool>{false, false, false}));
}

}  // namespace
}  // namespace ncpost::express
