// Configuration: parsing, overrides, and every error path names origin, key, value and domain.
#include "flexgait/core/config.hpp"

#include <unistd.h>  // getpid: a directory of this process alone (work trees run tests at once)

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace flexgait {
namespace {

Schema test_schema() {
  Schema s;
  return s.add(real_param("model.K", "1000.0", "N/m", "stiffness", 0, 1e9, false))
      .add(integer_param("model.legs", "10", "legs", 3, 100))
      .add(boolean_param("run.log", "true", "keep a log"))
      .add(choice_param("run.model", "flexible", "model", {"flexible", "rigid"}));
}

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto path =
      std::filesystem::temp_directory_path() / ("flexgait_config_test_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(path) << text;
  return path;
}

// Runs resolve_config and returns the ConfigError (fails the test if none is thrown).
ConfigError expect_error(const std::optional<std::filesystem::path>& file, const std::vector<std::string>& sets) {
  try {
    resolve_config(test_schema(), file, sets);
  } catch (const ConfigError& e) {
    return e;
  }
  ADD_FAILURE() << "no ConfigError thrown";
  return ConfigError("", "");
}

TEST(Config, DefaultsFileAndOverridesInOrder) {
  const auto file = write_temp("ok.yaml", "model:\n  K: 2500\n  legs: 12\nrun:\n  model: rigid\n");
  const Config c = resolve_config(test_schema(), file, {"model.K=3e3", "run.log=false"});
  EXPECT_EQ(c.real("model.K"), 3000.0);
  EXPECT_EQ(c.integer("model.legs"), 12);
  EXPECT_EQ(c.boolean("run.log"), false);
  EXPECT_EQ(c.choice("run.model"), "rigid");
  EXPECT_EQ(c.origin("model.K"), "--set");
  EXPECT_EQ(c.origin("model.legs"), file.string() + ":3");
}

TEST(Config, CrossFieldErrorNamesEveryKeysOrigin) {
  const auto file = write_temp("cross.yaml", "model:\n  K: 2500\n");
  const Config c = resolve_config(test_schema(), file, {"model.legs=4"});
  try {
    check_with_origin(c, [] { throw ConfigError("model.legs", "key 'model.legs' = '4': too few for model.K = 2500"); });
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "model.legs");
    EXPECT_EQ(std::string(e.what()),
              "--set: key 'model.legs' = '4': too few for model.K = 2500 (model.K from " + file.string() + ":2)");
  }
  try {  // a key named only inside a longer name is not named; one from the same origin adds nothing
    check_with_origin(c, [] { throw ConfigError("model.legs", "key 'model.legs': see model.K_max and run.model.x"); });
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "--set: key 'model.legs': see model.K_max and run.model.x");
  }
}

TEST(Config, DefaultIsBlamedOnTheValueGivenAgainstIt) {
  // model.legs keeps its default; the --set model.K is what made it wrong: the message leads with
  // "--set" and says model.legs is a default (no message starts with "default:").
  const Config c = resolve_config(test_schema(), std::nullopt, {"model.K=2500"});
  try {
    check_with_origin(c,
                      [] { throw ConfigError("model.legs", "key 'model.legs' = '10': too many for model.K = 2500"); });
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--set: key 'model.legs' = '10': too many for model.K = 2500 (model.legs from default)");
  }
  const Config d = resolve_config(test_schema(), std::nullopt, {});
  try {  // every value a default: no origin to blame but the defaults themselves
    check_with_origin(d, [] { throw ConfigError("model.legs", "key 'model.legs' = '10': bad"); });
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "the defaults: key 'model.legs' = '10': bad");
  }
}

Schema friction_schema() {
  Schema s;
  s.add(real_param("wheel.m", "1.0", "kg", "mass", 0, 1e9, false))
      .add(real_param("wheel.mu_s", "0.5", "", "static friction", 0, 10))
      .add(real_param("wheel.mu_k", "0.4", "", "kinetic friction", 0, 10))
      .add(real_param("wheel.omega", "1.0", "rad/s", "rate", -1e3, 1e3))
      .add(real_param("wheel.K", "1.0", "N/m", "stiffness", 0, 1e9, false));
  return s.alias("wheel.mu", {"wheel.mu_s", "wheel.mu_k"}, "both friction coefficients");
}

std::string unknown_key_message(const std::string& set) {
  try {
    resolve_config(friction_schema(), std::nullopt, {set});
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no ConfigError for " << set;
  return "";
}

TEST(Config, AliasSetsEachOfItsPartsAndNamesItselfInErrors) {
  const Config c = resolve_config(friction_schema(), std::nullopt, {"wheel.mu=0.13"});
  EXPECT_EQ(c.real("wheel.mu_s"), 0.13);
  EXPECT_EQ(c.real("wheel.mu_k"), 0.13);
  EXPECT_EQ(c.origin("wheel.mu_k"), "--set");
  EXPECT_EQ(c.to_yaml().find("mu:"), std::string::npos) << "an alias holds no value of its own";
  // Later --set wins, part by part.
  EXPECT_EQ(resolve_config(friction_schema(), std::nullopt, {"wheel.mu=0.3", "wheel.mu_k=0.2"}).real("wheel.mu_k"),
            0.2);
  const std::string bad = unknown_key_message("wheel.mu=-1");
  EXPECT_NE(bad.find("key 'wheel.mu' = '-1': out of range"), std::string::npos) << bad;
  Schema s = friction_schema();
  EXPECT_THROW(s.alias("wheel.mu", {"wheel.mu_s"}, ""), std::logic_error);           // taken
  EXPECT_THROW(s.alias("wheel.f", {"wheel.nope"}, ""), std::logic_error);            // of nothing
  EXPECT_THROW(s.add(real_param("wheel.mu", "1", "", "", 0, 1)), std::logic_error);  // a key named as an alias
  Schema merged;
  merged.merge(friction_schema());
  EXPECT_NE(merged.find_alias("wheel.mu"), nullptr);
}

TEST(Config, DidYouMeanOffersOnlyTheSameQuantity) {
  // A one-letter name is another quantity one edit away from most short names: wheel.mux is
  // offered mu_s and mu_k and the alias (edit distance 1-2), never the mass wheel.m.
  EXPECT_NE(unknown_key_message("wheel.mus=1").find("did you mean 'wheel.mu_s'"), std::string::npos);
  const std::string mux = unknown_key_message("wheel.mux=1");
  EXPECT_NE(mux.find("did you mean 'wheel.mu'?"), std::string::npos) << mux;
  EXPECT_EQ(mux.find("'wheel.m'"), std::string::npos) << mux;
  // A case slip of a one-letter name, and a section typo, are offered.
  EXPECT_NE(unknown_key_message("wheel.k=1").find("(did you mean 'wheel.K'?)"), std::string::npos);
  EXPECT_NE(unknown_key_message("wheal.omega=1").find("(did you mean 'wheel.omega'?)"), std::string::npos);
  // Equally near names are all offered.
  const std::string ties = unknown_key_message("wheel.mu_x=1");
  EXPECT_NE(ties.find("(did you mean 'wheel.mu_s' or 'wheel.mu_k'?)"), std::string::npos) << ties;
  // Nothing near: the message says where the keys are listed.
  const std::string far = unknown_key_message("nope=1");
  EXPECT_NE(far.find("`flexgait schema` lists every key"), std::string::npos) << far;
  EXPECT_EQ(far.find("did you mean"), std::string::npos) << far;
}

TEST(Config, ResolvedYamlRoundTripsExactly) {
  const Config c = resolve_config(test_schema(), std::nullopt, {"model.K=0.1"});
  const auto file = write_temp("roundtrip.yaml", c.to_yaml());
  const Config again = resolve_config(test_schema(), file, {});
  EXPECT_EQ(again.real("model.K"), 0.1);  // bit-identical: shortest round-trip text
  EXPECT_EQ(again.to_yaml(), c.to_yaml());
}

// A derived key (ParamSpec::derived): `auto` until set, `auto` again on request; its YAML says
// `auto` while it is derived, so a written configuration derives it again when read back.
TEST(Config, DerivedKeyIsAutoUntilSetAndRoundTripsAsAuto) {
  Schema s = test_schema();
  ParamSpec height = real_param("walk.height", "0.7", "m", "walking height", 0.1, 3);
  height.derived = "from the robot";
  s.add(height);
  Config c = resolve_config(s, std::nullopt, {});
  EXPECT_TRUE(c.derived("walk.height"));
  EXPECT_FALSE(c.derived("model.K"));
  EXPECT_NE(c.to_yaml().find("height: auto"), std::string::npos) << c.to_yaml();
  const Config again = resolve_config(s, write_temp("derived.yaml", c.to_yaml()), {});
  EXPECT_TRUE(again.derived("walk.height"));
  EXPECT_EQ(again.to_yaml(), c.to_yaml());

  c.set("walk.height", "0.65");
  EXPECT_FALSE(c.derived("walk.height"));
  EXPECT_EQ(c.real("walk.height"), 0.65);
  EXPECT_NE(c.to_yaml().find("height: 0.65"), std::string::npos);
  c.set("walk.height", "auto");
  EXPECT_TRUE(c.derived("walk.height"));
  EXPECT_EQ(c.origin("walk.height"), "--set");
  EXPECT_NE(height.allowed().find("or auto (from the robot)"), std::string::npos) << height.allowed();

  // A key that is not derived refuses `auto` as any other non-number.
  EXPECT_THROW(c.set("model.K", "auto"), ConfigError);
}

TEST(Config, UnknownKeyInFileIsAnError) {
  const auto file = write_temp("typo.yaml", "model:\n  legz: 5\n");
  const ConfigError e = expect_error(file, {});
  EXPECT_EQ(e.key(), "model.legz");
  EXPECT_NE(std::string(e.what()).find("unknown key 'model.legz'"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find(":2"), std::string::npos) << "names the line: " << e.what();
  EXPECT_NE(std::string(e.what()).find("did you mean 'model.legs'?"), std::string::npos) << e.what();
}

TEST(Config, UnknownKeyInOverrideIsAnError) {
  const ConfigError e = expect_error(std::nullopt, {"model.k=5"});
  EXPECT_EQ(e.key(), "model.k");
  EXPECT_NE(std::string(e.what()).find("--set"), std::string::npos);
}

TEST(Config, WrongTypeNamesKeyValueAndDomain) {
  const ConfigError e = expect_error(std::nullopt, {"model.K=stiff"});
  EXPECT_EQ(e.key(), "model.K");
  const std::string msg = e.what();
  EXPECT_NE(msg.find("'stiff'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("allowed: a finite real number in (0, 1000000000]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("N/m"), std::string::npos) << msg;
  EXPECT_EQ(expect_error(std::nullopt, {"model.legs=3.5"}).key(), "model.legs");
  EXPECT_EQ(expect_error(std::nullopt, {"run.log=yes"}).key(), "run.log");
  EXPECT_EQ(expect_error(std::nullopt, {"run.model=soft"}).key(), "run.model");
}

TEST(Config, OutOfRangeNanAndInfinityAreErrors) {
  for (const char* v : {"model.K=0", "model.K=-1", "model.K=nan", "model.K=inf", "model.K=1e10", "model.K="}) {
    const ConfigError e = expect_error(std::nullopt, {v});
    EXPECT_EQ(e.key(), "model.K") << v;
  }
  const ConfigError e = expect_error(std::nullopt, {"model.legs=2"});
  EXPECT_NE(std::string(e.what()).find("out of range; allowed: an integer in [3, 100]"), std::string::npos) << e.what();
}

TEST(Config, MalformedOverridesAndFiles) {
  EXPECT_NE(std::string(expect_error(std::nullopt, {"model.K"}).what()).find("key=value"), std::string::npos);
  const ConfigError missing = expect_error(std::filesystem::path("/nonexistent/flexgait.yaml"), {});
  EXPECT_NE(std::string(missing.what()).find("/nonexistent/flexgait.yaml: cannot read"), std::string::npos);
  const ConfigError syntax = expect_error(write_temp("bad.yaml", "model: [1, 2\n"), {});
  EXPECT_NE(std::string(syntax.what()).find("YAML syntax error"), std::string::npos) << syntax.what();
  EXPECT_EQ(expect_error(write_temp("list.yaml", "model:\n  K: [1, 2]\n"), {}).key(), "model.K");
  EXPECT_EQ(expect_error(write_temp("null.yaml", "model:\n  K:\n"), {}).key(), "model.K");
  EXPECT_NE(std::string(expect_error(write_temp("scalar.yaml", "42\n"), {}).what()).find("mapping"), std::string::npos);
}

TEST(Config, SchemaRejectsDuplicateKeysAndBadDefaults) {
  Schema s = test_schema();
  EXPECT_THROW(s.add(*s.find("model.K")), std::logic_error);
  EXPECT_THROW(s.add(real_param("x.y", "-1", "", "", 0, 1)), ConfigError);
}

}  // namespace
}  // namespace flexgait
