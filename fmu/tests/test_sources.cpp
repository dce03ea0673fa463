// The FMU's sources/ build the same plant (docs/fmu.md#sources): compiled as
// sources/buildDescription.xml says (its files, definitions, include
// folders and options, nothing else), the binary gives the bits of the
// shipped one.
#include <doctest/doctest.h>

#include <cstring>
#include <string>

#include "importer.hpp"

using namespace fmutest;

TEST_SUITE("sources") {
  TEST_CASE("the build description compiles into a binary with the shipped binary's bits") {
    const std::string dir = temp_dir("fmu-sources");
    const std::string out = dir + "/plant.fmu";
    REQUIRE(run(cvtplant() + " fmu --scene ratio-control --out " + out + " > /dev/null") == 0);
    const Unpacked fmu(out, dir + "/unpacked");
    pugi::xml_document bd;
    REQUIRE(bd.load_file((fmu.dir + "/sources/buildDescription.xml").c_str()));
    pugi::xml_node set = bd.child("fmiBuildDescription").child("BuildConfiguration").child("SourceFileSet");
    REQUIRE(std::string(set.attribute("language").value()) == "C++17");
    const std::string src = fmu.dir + "/sources/";
    std::string cmd = "c++ -std=c++17 -shared -fPIC -fvisibility=hidden " + std::string(set.attribute("compilerOptions").value());
    for (pugi::xml_node d : set.children("PreprocessorDefinition")) {
      cmd += std::string(" -D") + d.attribute("name").value();
      if (d.attribute("value")) cmd += std::string("=") + d.attribute("value").value();
    }
    for (pugi::xml_node d : set.children("IncludeDirectory")) cmd += " -I" + src + d.attribute("name").value();
    for (pugi::xml_node f : set.children("SourceFile")) cmd += " " + src + f.attribute("name").value();
    const std::string so = dir + "/from-sources.so";
    cmd += " -o " + so + " 2> " + dir + "/compile.txt";
    REQUIRE_MESSAGE(run(cmd) == 0, "compile failed: see " << dir << "/compile.txt");

    const Api3 shipped(fmu.binary()), built(so);
    Instance3 a(shipped, fmu, "shipped"), b(built, fmu, "built");
    REQUIRE(a.ok());
    REQUIRE_MESSAGE(b.ok(), b.log.all());
    REQUIRE(a.init() == fmi3OK);
    REQUIRE(b.init() == fmi3OK);
    const double h = fmu.frame_s;
    int compared = 0;
    for (long i = 0; i < 600; i += 3) {
      REQUIRE(a.step(i * h, 3 * h) == fmi3OK);
      REQUIRE(b.step(i * h, 3 * h) == fmi3OK);
      for (const VarInfo& v : fmu.vars) {
        if (v.type != "Float64" || v.causality != "output") continue;
        const double x = a.real(v.name), y = b.real(v.name);
        INFO(v.name << " at frame " << i + 3);
        CHECK(std::memcmp(&x, &y, sizeof x) == 0);
        ++compared;
      }
    }
    CHECK(compared > 4000);
    // The sources build has this scene's plant only: another scene's FMU
    // files are refused at instantiation, never run with the wrong plant.
    const std::string other = dir + "/other.fmu";
    REQUIRE(run(cvtplant() + " fmu --scene clamp-step --out " + other + " > /dev/null") == 0);
    const Unpacked clamp_step(other, dir + "/other");
    Instance3 c(built, clamp_step, "other");
    CHECK(!c.ok());
    CHECK(c.log.has("another scene's scalar or features"));
  }
}
