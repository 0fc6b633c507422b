// The loader's scan of description text (twin/robot_loader_xml.hpp): attributes with their lines,
// comments and CDATA skipped; numbers that are not finite found; MuJoCo 3 text translated in place
// (each line where it was), missing meshes dropped with the geoms that show them.
#include "flexgait/twin/robot_loader_xml.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace flexgait::twin {
namespace {

TEST(RobotLoaderXml, AttributesWithTheirLinesCommentsSkipped) {
  const std::string text = "<a x=\"1\">\n<!-- <b y=\"nan\"/> -->\n<c\n  z='2 3'/><![CDATA[<d w=\"4\">]]></a>";
  std::vector<std::string> seen;
  for_each_xml_attribute(text, [&](const XmlAttribute& a) {
    seen.push_back(std::string(a.element) + "." + std::string(a.name) + "=" + std::string(a.value) + "@" +
                   std::to_string(a.line));
  });
  EXPECT_EQ(seen, (std::vector<std::string>{"a.x=1@1", "c.z=2 3@4"}));
}

TEST(RobotLoaderXml, NonFiniteTokens) {
  EXPECT_EQ(non_finite_token("0 1 2"), "");
  EXPECT_EQ(non_finite_token("0 NaN 1"), "NaN");
  EXPECT_EQ(non_finite_token("-inf"), "-inf");
  EXPECT_EQ(non_finite_token("1e999"), "1e999");
  EXPECT_EQ(non_finite_token("banana infinity-ish"), "");  // not numbers at all
  EXPECT_TRUE(names_something("name"));
  EXPECT_FALSE(names_something("mass"));
}

TEST(RobotLoaderXml, MuJoCo3TranslatedInPlace) {
  const std::string text =
      "<mujoco>\n<option integrator=\"implicitfast\"/>\n<worldbody><body><joint range=\"0 1\" actuatorfrcrange=\"-1 "
      "1\"/>"
      "</body></worldbody>\n</mujoco>";
  std::vector<std::string> warnings;
  const std::string out = translate_mujoco3(text, warnings);
  EXPECT_EQ(out,
            "<mujoco><compiler autolimits=\"true\"/>\n<option integrator=\"implicit\"/>\n<worldbody><body><joint "
            "range=\"0 1\" user=\"-1 1\"/></body></worldbody>\n</mujoco>");
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[0].rfind("line 3: actuatorfrcrange read as the joint's torque limit", 0), 0u) << warnings[0];
  EXPECT_EQ(warnings[1].rfind("line 2: integrator=implicitfast taken as \"implicit\"", 0), 0u) << warnings[1];
  // A file whose joints carry user data of their own: the force range is dropped (it cannot ride in user).
  std::string with_user = text;
  with_user.replace(with_user.find("<joint "), 7, "<joint user=\"7\" ");
  warnings.clear();
  EXPECT_FALSE(joint_force_ranges_as_user(with_user));
  EXPECT_EQ(translate_mujoco3(with_user, warnings).find("actuatorfrcrange"), std::string::npos);
  EXPECT_EQ(warnings[0].rfind("line 3: actuatorfrcrange dropped", 0), 0u) << warnings[0];
  // A compiler that says autolimits: nothing added, nothing to warn.
  warnings.clear();
  const std::string plain = "<mujoco><compiler autolimits=\"false\"/></mujoco>";
  EXPECT_EQ(translate_mujoco3(plain, warnings), plain);
  EXPECT_TRUE(warnings.empty());
}

TEST(RobotLoaderXml, MissingMeshesAndTheirGeomsDropped) {
  const std::string text =
      "<mujoco><compiler autolimits=\"true\" meshdir=\"assets\"/><asset><mesh name=\"m\" file=\"no.stl\"/></asset>"
      "<worldbody><geom mesh=\"m\"/><geom type=\"box\" size=\"1 1 1\"/></worldbody></mujoco>";
  std::vector<std::string> warnings;
  EXPECT_EQ(translate_mujoco3(text, warnings, "/no/such/dir"),
            "<mujoco><compiler autolimits=\"true\" meshdir=\"assets\"/><asset></asset><worldbody><geom type=\"box\" "
            "size=\"1 1 1\"/></worldbody></mujoco>");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("1 mesh files not found (first: m); they and the 1 geoms"), std::string::npos)
      << warnings[0];
}

}  // namespace
}  // namespace flexgait::twin
