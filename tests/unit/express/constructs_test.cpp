// Each EXPRESS construct on a small schema written for the test: what the parser keeps.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "test_support.hpp"

namespace ncpost::express {
namespace {

using Strings = std::vector<std::string>;

std::vector<std::string> names_of(const SchemaSet& set, const std::vector<DeclRef>& refs) {
  std::vector<std::string> out;
  for (const DeclRef ref : refs) out.emplace_back(set.name_of(ref));
  return out;
}

TEST(express_parse, SchemaNameVersionAndLowerCaseIdentifiers) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA My_Schema '{ iso standard 10303 part(11) version(4) }';
    ENTITY Cartesian_POINT; Coordinates : LIST [1:3] OF REAL; END_ENTITY;
    END_SCHEMA;)");
  const Schema& schema = result.schemas.schemas().at(0);
  EXPECT_EQ(schema.name, "my_schema");
  EXPECT_EQ(schema.version, "{ iso standard 10303 part(11) version(4) }");
  const Entity* point = result.schemas.find_entity("CARTESIAN_point");
  ASSERT_NE(point, nullptr);
  EXPECT_EQ(point->name, "cartesian_point");
  EXPECT_EQ(point->attributes.at(0).name, "coordinates");
  EXPECT_NE(point->attribute("COORDINATES"), nullptr);
  EXPECT_EQ(point->attribute("coordinate"), nullptr);
  EXPECT_EQ(point->pos.line, 3u);
}

TEST(express_parse, SeveralSchemasWithUseAndReferenceFrom) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA base_schema;
      TYPE label = STRING; END_TYPE;
      ENTITY named_thing; name : label; END_ENTITY;
      FUNCTION f(x : INTEGER) : INTEGER; RETURN (x); END_FUNCTION;
    END_SCHEMA;
    SCHEMA middle_schema;
      USE FROM base_schema (named_thing AS root_thing);
      REFERENCE FROM base_schema (label, f);
      ENTITY part SUBTYPE OF (root_thing); id : label; END_ENTITY;
    END_SCHEMA;
    SCHEMA top_schema;
      USE FROM middle_schema;   -- everything, including what middle_schema imports
      ENTITY special_part SUBTYPE OF (part, root_thing); extra : label; END_ENTITY;
    END_SCHEMA;)");
  const SchemaSet& set = result.schemas;
  ASSERT_EQ(set.schemas().size(), 3u);
  const auto middle = static_cast<std::uint32_t>(1);
  const auto top = static_cast<std::uint32_t>(2);

  const auto root = set.resolve(middle, "Root_Thing");
  ASSERT_TRUE(root.has_value());
  EXPECT_EQ(root->kind, DeclKind::Entity);
  EXPECT_EQ(set.name_of(*root), "named_thing");
  EXPECT_EQ(root->schema, 0u);
  EXPECT_FALSE(set.resolve(middle, "named_thing").has_value()) << "imported only under its alias";
  EXPECT_EQ(set.resolve(middle, "f")->kind, DeclKind::Function);

  // Imports of imports: top_schema sees label and root_thing through middle_schema.
  EXPECT_TRUE(set.resolve(top, "label").has_value());
  const Entity* special = set.find_entity("special_part");
  ASSERT_NE(special, nullptr);
  EXPECT_EQ(test::attribute_names(*special), (Strings{"name", "id", "extra"}));
  EXPECT_EQ(test::owners(*special), (Strings{"named_thing", "part", "special_part"}));
  EXPECT_TRUE(set.is_subtype_of("special_part", "named_thing"));
}

TEST(express_parse, Constants) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA s;
    CONSTANT
      two_pi : REAL := 2.0 * PI;
      origin : LIST [3:3] OF REAL := [0.0, 0.0, sqrt(0.0)];
      dummy : thing := thing('x') || other();
    END_CONSTANT;
    ENTITY thing; n : STRING; END_ENTITY;
    ENTITY other; END_ENTITY;
    END_SCHEMA;)");
  const auto& constants = result.schemas.schemas().at(0).constants;
  ASSERT_EQ(constants.size(), 3u);
  EXPECT_EQ(constants[0].name, "two_pi");
  EXPECT_EQ(constants[0].type.kind, TypeKind::Real);
  EXPECT_EQ(constants[0].value.text, "2.0 * PI");
  EXPECT_EQ(to_express(constants[1].type), "LIST [3:3] OF REAL");
  EXPECT_EQ(constants[1].value.text, "[0.0, 0.0, SQRT(0.0)]");
  EXPECT_EQ(constants[2].value.text, "thing('x') || other()");
}

TEST(express_parse, SimpleTypes) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA s;
    TYPE t_integer = INTEGER; END_TYPE;
    TYPE t_real = REAL(6); END_TYPE;
    TYPE t_number = NUMBER; END_TYPE;
    TYPE t_string = STRING(80) FIXED; END_TYPE;
    TYPE t_binary = BINARY(32); END_TYPE;
    TYPE t_boolean = BOOLEAN; END_TYPE;
    TYPE t_logical = logical; END_TYPE;
    END_SCHEMA;)");
  const auto& types = result.schemas.schemas().at(0).types;
  ASSERT_EQ(types.size(), 7u);
  const std::vector<TypeKind> expected = {TypeKind::Integer, TypeKind::Real,   TypeKind::Number,
                                          TypeKind::String,  TypeKind::Binary, TypeKind::Boolean,
                                          TypeKind::Logical};
  for (std::size_t i = 0; i < types.size(); ++i) EXPECT_EQ(types[i].underlying.kind, expected[i]);
  EXPECT_EQ(types[1].underlying.width->text, "6");
  EXPECT_FALSE(types[1].underlying.fixed);
  EXPECT_EQ(types[3].underlying.width->text, "80");
  EXPECT_TRUE(types[3].underlying.fixed);
  EXPECT_FALSE(types[4].underlying.fixed);
  EXPECT_EQ(to_express(types[3].underlying), "STRING (80) FIXED");
}

TEST(express_parse, AggregateTypesWithBoundsAndFlags) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA s;
    CONSTANT n_max : INTEGER := 4; END_CONSTANT;
    TYPE a1 = ARRAY [1:3] OF OPTIONAL UNIQUE REAL; END_TYPE;
    TYPE l1 = LIST [0:?] OF UNIQUE LIST [2:2] OF INTEGER; END_TYPE;
    TYPE s1 = SET OF STRING; END_TYPE;
    TYPE b1 = BAG [1:n_max * 2] OF a1; END_TYPE;
    END_SCHEMA;)");
  const auto& types = result.schemas.schemas().at(0).types;
  const TypeSpec& array = types[0].underlying;
  EXPECT_EQ(array.kind, TypeKind::Aggregate);
  EXPECT_EQ(array.aggregate, AggregateKind::Array);
  EXPECT_EQ(array.lower->value, 1);
  EXPECT_EQ(array.upper->value, 3);
  EXPECT_TRUE(array.optional_elements);
  EXPECT_TRUE(array.unique_elements);

  const TypeSpec& list = types[1].underlying;
  EXPECT_TRUE(list.upper->indeterminate());
  EXPECT_FALSE(list.upper->value.has_value());
  EXPECT_TRUE(list.unique_elements);
  ASSERT_NE(list.element, nullptr);
  EXPECT_EQ(list.element->aggregate, AggregateKind::List);
  EXPECT_EQ(list.element->element->kind, TypeKind::Integer);
  EXPECT_EQ(to_express(list), "LIST [0:?] OF UNIQUE LIST [2:2] OF INTEGER");

  EXPECT_FALSE(types[2].underlying.lower.has_value());
  EXPECT_EQ(to_express(types[2].underlying), "SET OF STRING");
  EXPECT_EQ(types[3].underlying.upper->text, "n_max * 2");
  EXPECT_FALSE(types[3].underlying.upper->value.has_value());
}

TEST(express_parse, DefinedTypesAndTheirUnderlyingType) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA s;
    TYPE length_measure = REAL; END_TYPE;
    TYPE positive_length_measure = length_measure;
    WHERE
      WR1: SELF > 0.;
    END_TYPE;
    TYPE lengths = LIST [1:?] OF positive_length_measure; END_TYPE;
    END_SCHEMA;)");
  const SchemaSet& set = result.schemas;
  const TypeDecl* positive = set.find_type("positive_length_measure");
  ASSERT_NE(positive, nullptr);
  EXPECT_EQ(positive->underlying.kind, TypeKind::Named);
  EXPECT_EQ(positive->underlying.name, "length_measure");
  EXPECT_EQ(set.underlying_type(*positive).kind, TypeKind::Real);
  ASSERT_EQ(positive->where_rules.size(), 1u);
  EXPECT_EQ(positive->where_rules[0].label, "wr1");
  EXPECT_EQ(positive->where_rules[0].expression.text, "SELF > 0.");
  // An aggregate is where the chain stops.
  EXPECT_EQ(set.underlying_type(*set.find_type("lengths")).kind, TypeKind::Aggregate);
}

TEST(express_parse, SelectTypesExtensibleGenericEntityAndBasedOn) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA s;
    ENTITY circle; END_ENTITY;
    ENTITY square; END_ENTITY;
    ENTITY triangle; END_ENTITY;
    TYPE length_measure = REAL; END_TYPE;
    TYPE square_select = SELECT (square); END_TYPE;
    TYPE shape_select = SELECT (circle, square_select, Circle); END_TYPE;
    TYPE open_select = EXTENSIBLE SELECT (square); END_TYPE;
    TYPE wider_select = SELECT BASED_ON open_select WITH (circle, length_measure); END_TYPE;
    TYPE any_item = EXTENSIBLE GENERIC_ENTITY SELECT; END_TYPE;
    TYPE some_items = EXTENSIBLE GENERIC_ENTITY SELECT BASED_ON any_item WITH (triangle); END_TYPE;
    END_SCHEMA;)");
  const SchemaSet& set = result.schemas;
  EXPECT_EQ(names_of(set, set.select_leaves(*set.find_type("shape_select"))),
            (Strings{"circle", "square"}));
  const TypeDecl* open = set.find_type("open_select");
  EXPECT_TRUE(open->select.extensible);
  EXPECT_FALSE(open->select.generic_entity);
  // An extensible SELECT also admits what its extensions add, and the extension its base.
  EXPECT_EQ(names_of(set, set.select_leaves(*open)),
            (Strings{"square", "circle", "length_measure"}));
  const TypeDecl* wider = set.find_type("wider_select");
  ASSERT_TRUE(wider->select.based_on.has_value());
  EXPECT_EQ(wider->select.based_on->name, "open_select");
  EXPECT_EQ(names_of(set, set.select_leaves(*wider)),
            (Strings{"circle", "length_measure", "square"}));
  const TypeDecl* any = set.find_type("any_item");
  EXPECT_TRUE(any->select.generic_entity);
  EXPECT_TRUE(any->select.items.empty());
  EXPECT_EQ(names_of(set, set.select_leaves(*any)), (Strings{"triangle"}));
  EXPECT_TRUE(set.select_leaves(*set.find_type("length_measure")).empty());
}

TEST(express_parse, EnumerationsExtensibleAndBasedOn) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA s;
    TYPE colour = EXTENSIBLE ENUMERATION OF (Red, green); END_TYPE;
    TYPE more_colour = ENUMERATION BASED_ON colour WITH (blue, red); END_TYPE;
    TYPE future_colour = EXTENSIBLE ENUMERATION; END_TYPE;
    TYPE side = ENUMERATION OF (left, right); END_TYPE;
    END_SCHEMA;)");
  const SchemaSet& set = result.schemas;
  const TypeDecl* colour = set.find_type("colour");
  EXPECT_TRUE(colour->enumeration.extensible);
  EXPECT_EQ(colour->enumeration.items, (Strings{"red", "green"}));
  EXPECT_EQ(set.enumeration_items(*colour), (Strings{"red", "green", "blue"}));
  EXPECT_EQ(set.enumeration_items(*set.find_type("more_colour")),
            (Strings{"red", "green", "blue"}));
  EXPECT_TRUE(set.find_type("future_colour")->enumeration.items.empty());
  EXPECT_EQ(set.enumeration_items(*set.find_type("side")), (Strings{"left", "right"}));
}

TEST(express_parse, EntityHeaderSupertypeExpressions) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA s;
    ENTITY shape ABSTRACT SUPERTYPE OF (ONEOF (circle, square) ANDOR (filled AND outlined));
    END_ENTITY;
    ENTITY circle SUBTYPE OF (shape); END_ENTITY;
    ENTITY square SUBTYPE OF (shape); END_ENTITY;
    ENTITY filled SUBTYPE OF (shape); END_ENTITY;
    ENTITY outlined SUBTYPE OF (shape); END_ENTITY;
    ENTITY open_shape ABSTRACT SUPERTYPE; END_ENTITY;
    ENTITY thing2004 ABSTRACT; END_ENTITY;
    ENTITY concrete SUPERTYPE OF (ONEOF (c1)); END_ENTITY;
    ENTITY c1 SUBTYPE OF (concrete); END_ENTITY;
    END_SCHEMA;)");
  const SchemaSet& set = result.schemas;
  const Entity* shape = set.find_entity("shape");
  EXPECT_TRUE(shape->is_abstract);
  EXPECT_TRUE(shape->declares_supertype);
  ASSERT_TRUE(shape->subtype_constraint.has_value());
  const SupertypeExpression& andor = *shape->subtype_constraint;
  ASSERT_EQ(andor.op, SupertypeExpression::Op::AndOr);
  ASSERT_EQ(andor.operands.size(), 2u);
  EXPECT_EQ(andor.operands[0].op, SupertypeExpression::Op::OneOf);
  EXPECT_EQ(andor.operands[0].operands[1].entity.name, "square");
  EXPECT_EQ(andor.operands[1].op, SupertypeExpression::Op::And);
  EXPECT_EQ(andor.operands[1].operands[0].entity.name, "filled");
  EXPECT_EQ(names_of(set, shape->subtypes), (Strings{"circle", "square", "filled", "outlined"}));

  const Entity* open = set.find_entity("open_shape");
  EXPECT_TRUE(open->is_abstract && open->declares_supertype && !open->subtype_constraint);
  const Entity* thing = set.find_entity("thing2004");
  EXPECT_TRUE(thing->is_abstract && !thing->declares_supertype);
  const Entity* concrete = set.find_entity("concrete");
  EXPECT_FALSE(concrete->is_abstract);
  EXPECT_TRUE(concrete->declares_supertype);
}

TEST(express_parse, ExplicitAttributesOptionalAndShared) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA s;
    ENTITY point;
      x, y, z : REAL;
      label   : OPTIONAL STRING;
    END_ENTITY;
    END_SCHEMA;)");
  const Entity* point = result.schemas.find_entity("point");
  ASSERT_EQ(point->explicit_attributes.size(), 4u);
  EXPECT_EQ(test::attribute_names(*point), (Strings{"x", "y", "z", "label"}));
  EXPECT_FALSE(point->attributes[2].optional);
  EXPECT_TRUE(point->attributes[3].optional);
  EXPECT_EQ(point->explicit_attributes[1].pos.line, 4u);
  EXPECT_EQ(point->explicit_attributes[1].pos.column, 10u);
}

TEST(express_parse, DeriveInverseUniqueAndWhereClauses) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA s;
    ENTITY person;
      id       : STRING;
      given    : STRING;
      employer : OPTIONAL company;
    DERIVE
      initials : STRING := given[1];
    INVERSE
      owns      : SET [0:?] OF car FOR owner;
      main_car  : car FOR driver;
      all_roles : BAG [1:?] OF role FOR person.who;
    UNIQUE
      ur1 : id;
      given, SELF\person.employer;
    WHERE
      wr1 : EXISTS(id) AND (SIZEOF(owns) < 10);
      'a' <> given;
    END_ENTITY;
    ENTITY company; name : STRING; END_ENTITY;
    ENTITY car; owner : person; driver : person; END_ENTITY;
    ENTITY role; who : person; END_ENTITY;
    END_SCHEMA;)");
  const Entity* person = result.schemas.find_entity("person");
  ASSERT_EQ(person->derived_attributes.size(), 1u);
  EXPECT_EQ(person->derived_attributes[0].name, "initials");
  EXPECT_EQ(person->derived_attributes[0].expression.text, "given[1]");

  ASSERT_EQ(person->inverse_attributes.size(), 3u);
  const InverseAttribute& owns = person->inverse_attributes[0];
  EXPECT_EQ(owns.aggregate, AggregateKind::Set);
  EXPECT_EQ(owns.lower->value, 0);
  EXPECT_TRUE(owns.upper->indeterminate());
  EXPECT_EQ(owns.entity.name, "car");
  EXPECT_EQ(owns.for_attribute, "owner");
  EXPECT_FALSE(person->inverse_attributes[1].aggregate.has_value());
  EXPECT_EQ(person->inverse_attributes[2].aggregate, AggregateKind::Bag);
  EXPECT_EQ(person->inverse_attributes[2].for_attribute, "who");

  ASSERT_EQ(person->unique_rules.size(), 2u);
  EXPECT_EQ(person->unique_rules[0].label, "ur1");
  EXPECT_EQ(person->unique_rules[1].label, "");
  ASSERT_EQ(person->unique_rules[1].attributes.size(), 2u);
  EXPECT_EQ(person->unique_rules[1].attributes[1].entity, "person");
  EXPECT_EQ(person->unique_rules[1].attributes[1].attribute, "employer");

  ASSERT_EQ(person->where_rules.size(), 2u);
  EXPECT_EQ(person->where_rules[0].label, "wr1");
  EXPECT_EQ(person->where_rules[0].expression.text, "EXISTS(id) AND (SIZEOF(owns) < 10)");
  EXPECT_EQ(person->where_rules[1].label, "");
  EXPECT_EQ(person->where_rules[1].expression.text, "'a' <> given");
  // Only explicit attributes take a position in the instance.
  EXPECT_EQ(test::attribute_names(*person), (Strings{"id", "given", "employer"}));
}

TEST(express_parse, AlgorithmsAreKeptByNameAndSkippedAsBalancedBlocks) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA s;
    FUNCTION outer (a : BAG OF GENERIC : t) : SET OF GENERIC : t;
      FUNCTION inner (x : INTEGER) : INTEGER;
        PROCEDURE deepest (VAR y : INTEGER);
          y := y + 1;
        END_PROCEDURE;
        RETURN (x);
      END_FUNCTION;
      LOCAL r : SET OF GENERIC : t := []; END_LOCAL;
      IF SIZEOF(a) > 0 THEN
        REPEAT i := 1 TO HIINDEX(a); r := r + a[i]; END_REPEAT;
      END_IF;
      RETURN (r);  -- 'END_FUNCTION;' in a string or remark is no end: (* END_FUNCTION; *)
    END_FUNCTION;
    PROCEDURE p; END_PROCEDURE;
    RULE max_one FOR (thing, other);
      WHERE wr1 : SIZEOF(thing) <= 1;
    END_RULE;
    SUBTYPE_CONSTRAINT sc FOR thing; ABSTRACT SUPERTYPE; END_SUBTYPE_CONSTRAINT;
    ENTITY thing; END_ENTITY;
    ENTITY other; END_ENTITY;
    END_SCHEMA;)");
  const Schema& schema = result.schemas.schemas().at(0);
  ASSERT_EQ(schema.algorithms.size(), 4u);
  EXPECT_EQ(schema.algorithms[0].name, "outer");
  EXPECT_EQ(schema.algorithms[0].kind, AlgorithmKind::Function);
  EXPECT_EQ(schema.algorithms[1].kind, AlgorithmKind::Procedure);
  EXPECT_EQ(schema.algorithms[2].kind, AlgorithmKind::Rule);
  ASSERT_EQ(schema.algorithms[2].applies_to.size(), 2u);
  EXPECT_EQ(schema.algorithms[2].applies_to[1].name, "other");
  EXPECT_EQ(schema.algorithms[3].kind, AlgorithmKind::SubtypeConstraint);
  EXPECT_EQ(schema.algorithms[3].applies_to.at(0).name, "thing");
  EXPECT_EQ(schema.entities.size(), 2u);
  EXPECT_EQ(result.schemas.resolve(0, "outer")->kind, DeclKind::Function);
}

}  // namespace
}  // namespace ncpost::express
