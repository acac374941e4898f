"""The look of a figure, as siloscope's pictures have it (app/services/looks.h): a dark background for dark
slides and a text size. The C++ side passes it to the figure scripts as one argument,
"background=dark;font_scale=2"; an empty one is the default look (white, 1x). A journal figure adds its width on
the page, ";width_pt=241" (--width): its text is then 7 to 9 pt at that width, whatever the text size.

A figure's key (read_key) is what the bitmap pictures' legend and scale bar say, as tab-separated lines the C++
side writes: background, font_scale, info, species, arch, colorbar and scale, and width_pt for a journal figure."""
import sys


class Look:
    def __init__(self, spec=""):
        fields = dict(item.split("=", 1) for item in (spec or "").split(";") if "=" in item)
        self.dark = fields.get("background", "white") == "dark"
        self.font_scale = float(fields.get("font_scale", "1"))
        self.width_pt = float(fields.get("width_pt", "0"))  # > 0: a journal figure this wide
        self.fg = "#e6e6e6" if self.dark else "#000000"
        self.muted = "#aaaaaa" if self.dark else "#444444"
        self.bg = "#14161a" if self.dark else "#ffffff"
        self.frame = "#666666" if self.dark else "#999999"

    @property
    def journal(self):
        return self.width_pt > 0

    def size(self, points):
        """A font size of the default look (6 pt footers to 9 pt titles), in this look: at a journal width the
        same order of sizes within 7 to 9 pt (a journal's smallest legible text is 7 pt at print size)."""
        if self.journal:
            return 7.0 + (min(max(points, 6.0), 9.0) - 6.0) * 2.0 / 3.0
        return points * self.font_scale

    def apply(self, plt):
        """matplotlib's defaults in this look: background, text, axes and ticks."""
        plt.rcParams.update({"font.size": self.size(plt.rcParams["font.size"])})
        if self.journal:  # ticks, legends and labels at 7-9 pt too ("medium" is font.size)
            plt.rcParams.update({"legend.fontsize": self.size(7), "xtick.labelsize": self.size(7.5),
                                 "ytick.labelsize": self.size(7.5), "axes.titlesize": self.size(9),
                                 "axes.labelsize": self.size(8)})
        if not self.dark:
            return
        plt.rcParams.update({
            "figure.facecolor": self.bg, "axes.facecolor": self.bg, "savefig.facecolor": self.bg,
            "text.color": self.fg, "axes.labelcolor": self.fg, "axes.edgecolor": self.frame,
            "xtick.color": self.fg, "ytick.color": self.fg, "legend.facecolor": self.bg,
            "legend.edgecolor": self.frame, "grid.color": "#555555"})


def read_key(path, who):
    """A figure's key file -> {background, font_scale, info, species, arch, colorbar, scale}."""
    key = {"background": "white", "font_scale": 1.0, "info": [], "species": [], "arch": [], "colorbar": None,
           "scale": None, "width_pt": 0.0}
    with open(path, encoding="utf-8") as f:
        for line in f.read().splitlines():
            parts = line.split("\t")
            kind = parts[0]
            if kind == "background" and len(parts) == 2:
                key["background"] = parts[1]
            elif kind == "font_scale" and len(parts) == 2:
                key["font_scale"] = float(parts[1])
            elif kind == "info" and len(parts) == 2:
                key["info"].append(parts[1])
            elif kind in ("species", "arch") and len(parts) == 3:
                key[kind].append((parts[1], parts[2]))
            elif kind == "colorbar" and len(parts) == 5:
                key["colorbar"] = (parts[1], float(parts[2]), float(parts[3]), parts[4])
            elif kind == "scale" and len(parts) == 3:
                key["scale"] = (float(parts[1]), parts[2])
            elif kind == "width_pt" and len(parts) == 2:  # frame --width: a journal figure this wide
                key["width_pt"] = float(parts[1])
            else:
                print(f"{who}: {path}: a line siloscope does not write: {line!r}", file=sys.stderr)
                sys.exit(2)
    return key
