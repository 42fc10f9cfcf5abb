# Reads EXR frames through Blender's own EXR reader and compositor, for
# tests/film/exr_compositor_test.cpp:
#   blender -b --factory-startup --python-exit-code 3 --python blender_read_exr.py --
#       OUT WIDTH HEIGHT FRAME...
# For each FRAME (numbered from 0) it loads the image (bpy.data.images.load), adds it to the
# compositor as an Image node, and renders each of the node's outputs through the Composite node
# to OUT/<number>/<output>.exr (32-bit float RGBA, WIDTH x HEIGHT: the frames' size, which bpy
# does not report for a multilayer image), listing the outputs in OUT/<number>/outputs.txt. The test reads those files back and checks their values: a pass
# Blender could not read is missing or black there.
import os
import sys

import bpy


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    out, width, height, frames = args[0], int(args[1]), int(args[2]), args[3:]
    scene = bpy.context.scene
    scene.use_nodes = True
    tree = scene.node_tree
    for node in list(tree.nodes):
        tree.nodes.remove(node)
    composite = tree.nodes.new("CompositorNodeComposite")
    composite.use_alpha = True
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    settings.color_mode = "RGBA"
    settings.exr_codec = "ZIP"
    # Float EXRs are written scene-linear whatever the view; Standard keeps it so for any
    # Blender that would apply one.
    scene.view_settings.view_transform = "Standard"
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    for number, frame in enumerate(frames):
        image = bpy.data.images.load(frame)
        node = tree.nodes.new("CompositorNodeImage")
        node.image = image
        folder = os.path.join(out, str(number))
        os.makedirs(folder, exist_ok=True)
        names = []
        for output in node.outputs:
            if not output.enabled:
                continue
            for link in list(tree.links):
                tree.links.remove(link)
            tree.links.new(output, composite.inputs["Image"])
            scene.render.filepath = os.path.join(folder, output.name + ".exr")
            bpy.ops.render.render(write_still=True)
            names.append(output.name)
        # Known once the compositor has read it.
        print("blender_read_exr: %s is %s" % (frame, image.type))
        with open(os.path.join(folder, "outputs.txt"), "w") as listing:
            listing.write("\n".join(names) + "\n")
        tree.nodes.remove(node)


main()
