"""The look of a figure, as siloscope's pictures have it (app/services/looks.h): a dark background for dark
slides and a text size. The C++ side passes it to the figure scripts as one argument,
"background=dark;font_scale=2"; an empty one is the default look (white, 1x)."""


class Look:
    def __init__(self, spec=""):
        fields = dict(item.split("=", 1) for item in (spec or "").split(";") if "=" in item)
        self.dark = fields.get("background", "white") == "dark"
        self.font_scale = float(fields.get("font_scale", "1"))
        self.fg = "#e6e6e6" if self.dark else "#000000"
        self.muted = "#aaaaaa" if self.dark else "#444444"
        self.bg = "#14161a" if self.dark else "#ffffff"
        self.frame = "#666666" if self.dark else "#999999"

    def size(self, points):
        """A font size of the default look, in this look."""
        return points * self.font_scale

    def apply(self, plt):
        """matplotlib's defaults in this look: background, text, axes and ticks."""
        plt.rcParams.update({"font.size": self.size(plt.rcParams["font.size"])})
        if not self.dark:
            return
        plt.rcParams.update({
            "figure.facecolor": self.bg, "axes.facecolor": self.bg, "savefig.facecolor": self.bg,
            "text.color": self.fg, "axes.labelcolor": self.fg, "axes.edgecolor": self.frame,
            "xtick.color": self.fg, "ytick.color": self.fg, "legend.facecolor": self.bg,
            "legend.edgecolor": self.frame, "grid.color": "#555555"})
