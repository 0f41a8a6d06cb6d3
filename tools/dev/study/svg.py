"""svg.py - log-log work-precision figures as standalone SVG (python3 stdlib only), for
tools/dev/study/study.py: labelled axes with units, decade ticks and grid, a legend, one line
with markers per series, starred and named points for the shipped configurations, a
shaded band below the smallest error the reference resolves, and an optional second x
axis on top (a fixed factor of the bottom one)."""
import math

COLORS = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2",
          "#17becf", "#7f7f7f", "#bcbd22", "#000000", "#aec7e8"]
MARKERS = ["o", "s", "^", "D", "v", "x", "+", "p"]


def esc(s):
    return str(s).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def marker(kind, x, y, color, r=4.0, filled=True):
    fill = color if filled else "white"
    st = 'fill="%s" stroke="%s" stroke-width="1.3"' % (fill, color)
    if kind == "o":
        return '<circle cx="%.1f" cy="%.1f" r="%.1f" %s/>' % (x, y, r, st)
    if kind == "s":
        return '<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" %s/>' % (
            x - r, y - r, 2 * r, 2 * r, st)
    if kind in "^vDp":
        if kind == "^":
            pts = [(x, y - r * 1.2), (x - r * 1.1, y + r * 0.8), (x + r * 1.1, y + r * 0.8)]
        elif kind == "v":
            pts = [(x, y + r * 1.2), (x - r * 1.1, y - r * 0.8), (x + r * 1.1, y - r * 0.8)]
        elif kind == "D":
            pts = [(x, y - r * 1.3), (x + r * 1.3, y), (x, y + r * 1.3), (x - r * 1.3, y)]
        else:
            pts = [(x + r * 1.2 * math.sin(a * 2 * math.pi / 5),
                    y - r * 1.2 * math.cos(a * 2 * math.pi / 5)) for a in range(5)]
        return '<polygon points="%s" %s/>' % (
            " ".join("%.1f,%.1f" % p for p in pts), st)
    if kind == "*":  # a five-pointed star
        pts = []
        for k in range(10):
            rr = r if k % 2 == 0 else r * 0.45
            a = k * math.pi / 5
            pts.append((x + rr * math.sin(a), y - rr * math.cos(a)))
        return '<polygon points="%s" fill="%s" stroke="black" stroke-width="1"/>' % (
            " ".join("%.1f,%.1f" % p for p in pts), color)
    d = r * 1.1  # x and +
    if kind == "x":
        segs = [(x - d, y - d, x + d, y + d), (x - d, y + d, x + d, y - d)]
    else:
        segs = [(x - d, y, x + d, y), (x, y - d, x, y + d)]
    return "".join('<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="%s" '
                   'stroke-width="2"/>' % (a, b, c, e, color) for a, b, c, e in segs)


def fmt_pow(e):
    return "10<tspan dy=\"-6\" font-size=\"10\">%d</tspan>" % e


def decades(lo, hi):
    return list(range(int(math.floor(math.log10(lo))), int(math.ceil(math.log10(hi))) + 1))


def plot(path, title, xlabel, ylabel, series, stars=(), band=None, top=None,
         xrange=None, yrange=None, note=None, w=960, h=620):
    """series: [{name, color, marker, dash, pts: [(x, y, label)]}]; stars: [(x, y, name)];
    band: (y_top, text) shaded from the bottom up to y_top; top: (factor, label) for a
    second x axis; ranges: (lo, hi) or None for automatic (whole decades)."""
    xs = [p[0] for s in series for p in s["pts"]] + [p[0] for p in stars]
    ys = [p[1] for s in series for p in s["pts"]] + [p[1] for p in stars]
    if not xs:
        xs, ys = [1, 10], [1e-3, 1e-2]
    x0, x1 = xrange or (10 ** math.floor(math.log10(min(xs))),
                        10 ** math.ceil(math.log10(max(xs))))
    y0, y1 = yrange or (10 ** math.floor(math.log10(min(ys))),
                        10 ** math.ceil(math.log10(max(ys))))
    if x1 <= x0 * 1.0001:
        x1 = x0 * 10
    if y1 <= y0 * 1.0001:
        y1 = y0 * 10
    ml, mr, mt, mb = 90, 300, 70 if top else 45, 65
    pw, ph = w - ml - mr, h - mt - mb
    lx0, lx1, ly0, ly1 = map(math.log10, (x0, x1, y0, y1))

    def X(v):
        return ml + (math.log10(v) - lx0) / (lx1 - lx0) * pw

    def Y(v):
        return mt + ph - (math.log10(v) - ly0) / (ly1 - ly0) * ph

    o = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" '
         'viewBox="0 0 %d %d" font-family="DejaVu Sans, Arial, sans-serif" font-size="12">'
         % (w, h, w, h), '<rect width="100%" height="100%" fill="white"/>',
         '<text x="%d" y="20" font-size="15" font-weight="bold">%s</text>' % (ml, esc(title))]
    o.append('<defs><clipPath id="pa"><rect x="%d" y="%d" width="%d" height="%d"/>'
             '</clipPath></defs>' % (ml, mt, pw, ph))
    if band and band[0] > y0:
        yb = min(band[0], y1)
        o.append('<rect x="%d" y="%.1f" width="%d" height="%.1f" fill="#eeeeee"/>'
                 % (ml, Y(yb), pw, mt + ph - Y(yb)))
        o.append('<text x="%d" y="%.1f" fill="#666" font-size="11">%s</text>'
                 % (ml + 6, mt + ph - 6, esc(band[1])))
    # grid and ticks
    for e in decades(x0, x1):
        v = 10.0 ** e
        if x0 <= v * 1.0001 and v <= x1 * 1.0001:
            o.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="#ccc"/>'
                     % (X(v), mt, X(v), mt + ph))
            o.append('<text x="%.1f" y="%d" text-anchor="middle">%s</text>'
                     % (X(v), mt + ph + 18, fmt_pow(e)))
        for k in range(2, 10):
            u = k * v
            if x0 < u < x1:
                o.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="#999"/>'
                         % (X(u), mt + ph, X(u), mt + ph - 4))
    for e in decades(y0, y1):
        v = 10.0 ** e
        if y0 <= v * 1.0001 and v <= y1 * 1.0001:
            o.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#ccc"/>'
                     % (ml, Y(v), ml + pw, Y(v)))
            o.append('<text x="%d" y="%.1f" text-anchor="end">%s</text>'
                     % (ml - 6, Y(v) + 4, fmt_pow(e)))
    if top:
        f, label = top
        for e in decades(x0 * f, x1 * f):
            v = 10.0 ** e
            if x0 * f <= v * 1.0001 and v <= x1 * f * 1.0001:
                o.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="#555"/>'
                         % (X(v / f), mt, X(v / f), mt + 5))
                o.append('<text x="%.1f" y="%d" text-anchor="middle">%s</text>'
                         % (X(v / f), mt - 8, fmt_pow(e)))
        o.append('<text x="%.1f" y="%d" text-anchor="middle">%s</text>'
                 % (ml + pw / 2, mt - 30, esc(label)))
    o.append('<rect x="%d" y="%d" width="%d" height="%d" fill="none" stroke="black"/>'
             % (ml, mt, pw, ph))
    o.append('<text x="%.1f" y="%d" text-anchor="middle">%s</text>'
             % (ml + pw / 2, h - 18, esc(xlabel)))
    o.append('<text transform="translate(22,%.1f) rotate(-90)" text-anchor="middle">%s</text>'
             % (mt + ph / 2, esc(ylabel)))
    # series
    o.append('<g clip-path="url(#pa)">')
    for s in series:
        pts = sorted(s["pts"])
        if len(pts) > 1:
            o.append('<polyline points="%s" fill="none" stroke="%s" stroke-width="1.5"%s/>'
                     % (" ".join("%.1f,%.1f" % (X(p[0]), Y(max(p[1], y0))) for p in pts),
                        s["color"], ' stroke-dasharray="6,3"' if s.get("dash") else ""))
        for p in pts:
            below = p[1] < y0
            o.append(marker(s["marker"], X(p[0]), Y(max(p[1], y0)), s["color"],
                            filled=not below))
    for x, y, name in stars:
        o.append(marker("*", X(x), Y(max(y, y0)), "#ffd700", r=11))
    o.append('</g>')
    for k, (x, y, name) in enumerate(stars):  # labels alternately above and below
        dy = -8 if k % 2 == 0 else 18
        o.append('<text x="%.1f" y="%.1f" font-size="11" font-weight="bold">%s</text>'
                 % (X(x) + 12, Y(max(y, y0)) + dy, esc(name)))
    # legend
    lx, ly = ml + pw + 15, mt + 8
    for s in series:
        o.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="%s" stroke-width="1.5"%s/>'
                 % (lx, ly, lx + 24, ly, s["color"],
                    ' stroke-dasharray="6,3"' if s.get("dash") else ""))
        o.append(marker(s["marker"], lx + 12, ly, s["color"]))
        o.append('<text x="%d" y="%d" font-size="11">%s</text>' % (lx + 30, ly + 4,
                                                                   esc(s["name"])))
        ly += 17
    if stars:
        o.append(marker("*", lx + 12, ly, "#ffd700", r=8))
        o.append('<text x="%d" y="%d" font-size="11">shipped scene</text>' % (lx + 30, ly + 4))
        ly += 17
    if note:
        for line in note:
            ly += 4
            o.append('<text x="%d" y="%d" font-size="10" fill="#444">%s</text>'
                     % (lx, ly + 4, esc(line)))
            ly += 13
    o.append('</svg>')
    with open(path, "w") as f:
        f.write("\n".join(o) + "\n")
