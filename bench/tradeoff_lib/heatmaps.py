"""The README figures of a full run: where the error is (lab 1 and lab 2).

Each figure shows a low-poly sphere's ideal reference, the lab's picture and lab_compare's
|error| heatmap side by side, written to OUT_DIR/NAME.png.
"""
import os


def sphere_scene(segments, rings, lit, shading="phong"):
    """One sphere filling the view; lit: Blinn-Phong under one point light, with `shading`."""
    scene = {
        "camera": {"mode": "lookat", "position": [0, 0, 2.2], "target": [0, 0, 0], "fov_y_deg": 40},
        "background": [0.02, 0.03, 0.06],
        "materials": {"m": {"albedo": [0.2, 0.4, 0.9], "specular": [0.6, 0.6, 0.6], "shininess": 48}},
        "objects": [{"mesh": "sphere", "material": "m", "segments": segments, "rings": rings}],
    }
    if lit:
        scene["ambient"] = {"color": [1, 1, 1], "intensity": 0.05}
        scene["lighting"] = {"model": "blinn_phong", "shading": shading}
        scene["lights"] = [{"type": "point", "position": [0.9, 0.8, 1.2], "color": [1, 1, 1], "intensity": 1.6,
                            "attenuation": [1, 0.2, 0.1]}]
    return scene


def heatmap_figure(runner, scene, name, title, out_dir, w=480, h=360):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import matplotlib.pyplot as plt

    path = runner.write_scene(scene, name)
    png = os.path.join(runner.tmp, name + ".png")
    runner.render(path, w, h, 1, png)
    truth = runner.truth(scene, w, h)
    heat = os.path.join(runner.tmp, name + "_heat.png")
    e = runner.compare_png(truth, png, heat)
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.5))
    for ax, img, label in zip(axes, [truth, png, heat], ["ideal (lab_reference --ideal)", "lab", "|error| heatmap"]):
        ax.imshow(mpimg.imread(img))
        ax.set_title(label, fontsize=9)
        ax.axis("off")
    fig.suptitle(f"{title}\nmean |error| {float(e['mean_abs']):.2f}/255, max {e['max_abs']}/255, "
                 f"{e['over_2']} of pixels above 2/255, mean CIEDE2000 {float(e['mean_de2000']):.2f}", fontsize=9)
    fig.tight_layout()
    out = os.path.join(out_dir, name + ".png")
    fig.savefig(out, dpi=80)
    plt.close(fig)
    print(f"  heatmap {out}: {e}")


def heatmaps(lab, runner, out_dir):
    """The lab's figures (none for labs 3 and 4)."""
    if lab == "lab1_camera":
        heatmap_figure(runner, sphere_scene(16, 8, lit=False), "lab1_sphere16_silhouette",
                       "a 16-segment sphere (16 × 8) against the ideal sphere: only the silhouette differs", out_dir)
    elif lab == "lab2_lighting":
        for shading in ("gouraud", "phong"):
            heatmap_figure(runner, sphere_scene(16, 8, lit=True, shading=shading), f"lab2_sphere16_{shading}",
                           f"{shading.capitalize()} shading of a 16 × 8 sphere under a point light against "
                           f"per-pixel shading of the ideal sphere", out_dir)
