#!/usr/bin/env python3
"""tools/check-layers.py refuses each way includes and DEPS can part, naming where."""
import pathlib
import shutil
import subprocess
import sys
import tempfile
import unittest

SOURCE = pathlib.Path(__file__).resolve().parents[2]
CHECK = SOURCE / "tools" / "check-layers.py"


def run_check(root):
    result = subprocess.run([sys.executable, str(CHECK), str(root)], capture_output=True,
                            text=True, check=False)
    return result.returncode, result.stderr


# Four libraries as the real tree has them, in small: camera and scene on core, render on scene.
# The comment inside scene's call names glint_camera after DEPS; read as words it would make a
# dependency nothing includes.
SMALL_CMAKE = """glint_library(core SOURCES core/a.cpp DEPS Threads::Threads)
glint_library(camera SOURCES camera/d.cpp DEPS glint_core)
glint_library(scene SOURCES scene/b.cpp
              DEPS glint_core # not glint_camera: scene/ does not include it
              )
glint_library(render SOURCES render/c.cpp DEPS glint_scene glint_core TBB::tbb)
"""
SMALL_FILES = {
    "core/a.h": "#pragma once\n",
    "core/a.cpp": '#include "core/a.h"\n#include <vector>\n',
    "camera/d.h": '#pragma once\n#include "core/a.h"\n',
    "scene/b.h": '#pragma once\n#include "core/a.h"\n#include "generated_header.h"\n',
    "render/c.cpp": '#include "scene/b.h"\n#include "core/a.h"\n',
}


class CheckLayersTest(unittest.TestCase):
    def setUp(self):
        self.root = pathlib.Path(tempfile.mkdtemp(prefix="check_layers_"))

    def tearDown(self):
        shutil.rmtree(self.root)

    def write_tree(self, cmake, files):
        (self.root / "renderer").mkdir()
        (self.root / "renderer" / "CMakeLists.txt").write_text(cmake)
        for path, text in files.items():
            (self.root / "renderer" / path).parent.mkdir(parents=True, exist_ok=True)
            (self.root / "renderer" / path).write_text(text)

    def test_real_tree_with_core_including_render_fails_naming_file_line_and_dependency(self):
        # A copy of the real renderer/ where core/vec.h, below everything, includes render/:
        # glint_core depends on no glint library, so this is the upward include the check stops.
        self.assertEqual(run_check(SOURCE), (0, ""), "the real tree must pass before planting")
        shutil.copytree(SOURCE / "renderer", self.root / "renderer")
        vec = self.root / "renderer" / "core" / "vec.h"
        lines = vec.read_text().splitlines(keepends=True)
        pragma = next(i for i, line in enumerate(lines) if line.startswith("#pragma once"))
        lines.insert(pragma + 1, '#include "render/render_job.h"\n')
        vec.write_text("".join(lines))
        code, errors = run_check(self.root)
        self.assertEqual(code, 1, errors)
        # The planted include is the line after #pragma once (lines count from 1).
        self.assertIn(f'renderer/core/vec.h:{pragma + 2}: #include "render/render_job.h": '
                      "glint_core does not depend on glint_render", errors)
        self.assertEqual(errors.count("does not depend on"), 1, errors)

    def test_small_tree_that_matches_passes(self):
        self.write_tree(SMALL_CMAKE, SMALL_FILES)
        self.assertEqual(run_check(self.root), (0, ""))

    def test_sideways_include_fails(self):
        # scene and camera both sit on core; scene's DEPS do not name camera.
        files = dict(SMALL_FILES, **{"scene/b.cpp": '\n#include "camera/d.h"\n'})
        self.write_tree(SMALL_CMAKE, files)
        code, errors = run_check(self.root)
        self.assertEqual(code, 1, errors)
        self.assertIn('renderer/scene/b.cpp:2: #include "camera/d.h": glint_scene does not depend '
                      "on glint_camera", errors)

    def test_include_reached_only_through_others_fails(self):
        # render reaches core through scene, but DEPS name what a folder includes itself.
        self.write_tree(SMALL_CMAKE.replace("DEPS glint_scene glint_core", "DEPS glint_scene"),
                        SMALL_FILES)
        code, errors = run_check(self.root)
        self.assertEqual(code, 1, errors)
        self.assertIn('renderer/render/c.cpp:2: #include "core/a.h": glint_core is reached only '
                      "through other libraries; name it in glint_render's DEPS", errors)
        self.assertNotIn("does not depend on", errors)

    def test_dependency_nothing_includes_fails(self):
        files = dict(SMALL_FILES, **{"render/c.cpp": '#include "scene/b.h"\n'})
        self.write_tree(SMALL_CMAKE, files)
        code, errors = run_check(self.root)
        self.assertEqual(code, 1, errors)
        self.assertIn("renderer/CMakeLists.txt:6: glint_render's DEPS name glint_core, but no "
                      "file of renderer/render/ includes it", errors)

    def test_cycle_fails(self):
        cmake = SMALL_CMAKE.replace("DEPS Threads::Threads", "DEPS glint_render Threads::Threads")
        self.write_tree(cmake, dict(SMALL_FILES, **{"core/a.cpp": '#include "render/c.h"\n'}))
        code, errors = run_check(self.root)
        self.assertEqual(code, 1, errors)
        self.assertIn("DEPS form a cycle: core -> render -> scene -> core", errors)

    def test_unclosed_call_is_refused_as_unreadable(self):
        self.write_tree("glint_library(core SOURCES core/a.cpp DEPS\n", SMALL_FILES)
        code, errors = run_check(self.root)
        self.assertEqual(code, 2, errors)
        self.assertIn("glint_library( is never closed", errors)


if __name__ == "__main__":
    unittest.main()
