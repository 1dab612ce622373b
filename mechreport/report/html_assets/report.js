/* mechreport's interactive pages (report.html, index.html): plain JavaScript, no library,
   no network. The report's data is the page's JSON block #mr-data (read as text, never run);
   every string from it is put in the page as text (textContent), never as markup. */
(function () {
  "use strict";
  var SVG = "http://www.w3.org/2000/svg";

  function el(tag, attrs, parent, ns) {
    var e = ns ? document.createElementNS(SVG, tag) : document.createElement(tag);
    for (var k in attrs) { if (Object.prototype.hasOwnProperty.call(attrs, k)) e.setAttribute(k, attrs[k]); }
    if (parent) parent.appendChild(e);
    return e;
  }
  function svg(tag, attrs, parent) { return el(tag, attrs, parent, true); }
  function text(node, s) { node.textContent = s; return node; }

  /* ------------------------------------------------------------------ report.html */
  function report(data) {
    var n = data.angles.length;
    if (!n) return;
    var slider = document.getElementById("angle");
    var out = document.getElementById("angle-out");
    var play = document.getElementById("play");
    var listeners = [];
    var current = 0;

    function setIndex(k) {
      current = Math.max(0, Math.min(n - 1, k));
      slider.value = String(current);
      listeners.forEach(function (f) { f(current); });
    }
    function nearestIndex(angle) {
      var best = 0;
      for (var i = 1; i < n; i++) {
        if (Math.abs(data.angles[i] - angle) < Math.abs(data.angles[best] - angle)) best = i;
      }
      return best;
    }
    function angleText(k) {
      var a = data.angles[k];
      var s = data.coord + " " + a + (data.unit === "°" ? "°" : data.unit);
      return data.near[k] ? s + " (near a left-out angle)" : s;
    }
    slider.addEventListener("input", function () { setIndex(parseInt(slider.value, 10)); });
    listeners.push(function (k) { text(out, angleText(k)); });

    var timer = null;
    var stride = Math.max(1, Math.round(n / 120));
    play.addEventListener("click", function () {
      if (timer !== null) { clearInterval(timer); timer = null; text(play, "▶ Play"); return; }
      text(play, "❚❚ Pause");
      timer = setInterval(function () { setIndex((current + stride) % n); }, 50);
    });

    valuesTable(data, listeners);
    mechanism(data, listeners);
    charts(data, listeners, setIndex, nearestIndex);
    window.mechreport = { setAngle: function (a) { setIndex(nearestIndex(a)); },
                          index: function () { return current; } };
    setIndex(0);
  }

  function valuesTable(data, listeners) {
    var body = document.querySelector("#values tbody");
    var rows = [];
    var er = el("tr", { "data-joint": "", "class": "effort" }, body);
    text(el("th", {}, er), data.effort.label + " [" + data.units.effort + "]");
    var ev = el("td", { "class": "num f" }, er);
    el("td", { "class": "num" }, er); el("td", { "class": "num" }, er);
    data.joints.forEach(function (j) {
      var tr = el("tr", { "data-joint": j.name }, body);
      var th = el("th", {}, tr);
      var key = svg("svg", { width: "10", height: "10", viewBox: "0 0 10 10", "class": "key" }, th);
      svg("rect", { width: "10", height: "10", fill: j.color }, key);
      th.appendChild(document.createTextNode(" " + j.symbol + " (" + j.name + ") [" + data.units.force + "]"));
      rows.push([j, el("td", { "class": "num f" }, tr), el("td", { "class": "num fx" }, tr),
                 el("td", { "class": "num fy" }, tr)]);
    });
    var sv = null;
    if (data.shaking) {
      var sr = el("tr", { "data-joint": "", "class": "shaking" }, body);
      text(el("th", {}, sr), data.shaking.label + " [" + data.units.force + "]");
      sv = el("td", { "class": "num f" }, sr);
      el("td", { "class": "num" }, sr); el("td", { "class": "num" }, sr);
    }
    listeners.push(function (k) {
      text(ev, data.effort.text[k]);
      if (sv) text(sv, data.shaking.text[k]);
      rows.forEach(function (r) {
        text(r[1], r[0].text.f[k]); text(r[2], r[0].text.fx[k]); text(r[3], r[0].text.fy[k]);
      });
    });
  }

  /* the mechanism at angle k, its joint reactions (colour per joint), loads (black) */
  function mechanism(data, listeners) {
    var g = data.geometry, G = g.grid;
    var root = document.getElementById("mech");
    var xs = [], ys = [];
    function seen(p) { if (p) { xs.push(p[0]); ys.push(p[1]); } }
    g.links.forEach(function (l) { l.points.forEach(function (path) { path.forEach(seen); }); });
    g.ground.forEach(seen);
    data.joints.forEach(function (j) { j.at.forEach(seen); });
    var pad = 0.28 * G;
    var x0 = Math.min.apply(null, xs) - pad, x1 = Math.max.apply(null, xs) + pad;
    var y0 = Math.min.apply(null, ys) - pad, y1 = Math.max.apply(null, ys) + pad;
    root.setAttribute("viewBox", [x0, -y1, x1 - x0, y1 - y0].join(" "));
    var w = G / 220;
    var layer = svg("g", {}, root);
    function P(p) { return p[0] + "," + (-p[1]); }
    function arrow(parent, at, fx, fy, color, label) {
      if (!at || fx === null || fy === null || !(g.force_ref > 0)) return;
      var f = Math.hypot(fx, fy);
      if (!(f > 0)) return;
      var len = g.arrow * G * f / g.force_ref, cut = len > g.clip * g.arrow * G;
      if (cut) len = g.clip * g.arrow * G;
      var ux = fx / f, uy = fy / f;
      var tip = [at[0] + ux * len, at[1] + uy * len];
      svg("line", { x1: at[0], y1: -at[1], x2: tip[0], y2: -tip[1], stroke: color,
                    "stroke-width": 2.2 * w, "stroke-dasharray": cut ? (6 * w) + " " + (3 * w) : "none" }, parent);
      var h = Math.min(0.35 * len, 0.045 * G), b = 0.4 * h;
      var base = [tip[0] - ux * h, tip[1] - uy * h];
      svg("polygon", { points: [P(tip), P([base[0] - uy * b, base[1] + ux * b]),
                                 P([base[0] + uy * b, base[1] - ux * b])].join(" "), fill: color }, parent);
      var t = svg("text", { x: tip[0] + ux * 0.03 * G, y: -(tip[1] + uy * 0.03 * G),
                            "font-size": 0.04 * G, fill: color, "text-anchor": "middle" }, parent);
      text(t, label);
    }
    listeners.push(function (k) {
      while (layer.firstChild) layer.removeChild(layer.firstChild);
      g.links.forEach(function (l) {
        var pts = l.points.map(function (path) { return path[k]; }).filter(Boolean);
        if (!pts.length) return;
        var closed = pts.length >= 3;
        svg(closed ? "polygon" : "polyline", { points: pts.map(P).join(" "),
            fill: closed ? "rgba(90,110,140,0.18)" : "none", stroke: "#3b4a5e",
            "stroke-width": 4 * w, "stroke-linejoin": "round", "stroke-linecap": "round" }, layer);
        if (pts.length === 1) {
          var s = 0.05 * G;
          svg("rect", { x: pts[0][0] - s, y: -pts[0][1] - 0.7 * s, width: 2 * s, height: 1.4 * s,
                        fill: "rgba(90,110,140,0.25)", stroke: "#3b4a5e", "stroke-width": 2 * w }, layer);
        }
      });
      g.ground.forEach(function (p) {
        var s = 0.03 * G;
        svg("polygon", { points: [P(p), P([p[0] - s, p[1] - 1.6 * s]), P([p[0] + s, p[1] - 1.6 * s])].join(" "),
                         fill: "#c8ccd2", stroke: "#555", "stroke-width": w }, layer);
      });
      data.joints.forEach(function (j) {
        var p = j.at[k];
        if (p) svg("circle", { cx: p[0], cy: -p[1], r: 0.012 * G, fill: "#fff", stroke: "#222", "stroke-width": 1.5 * w }, layer);
      });
      data.joints.forEach(function (j) { arrow(layer, j.at[k], j.fx[k], j.fy[k], j.color, j.symbol); });
      g.loads.forEach(function (l) { arrow(layer, l.at[k], l.fx[k], l.fy[k], l.color, l.symbol); });
    });
  }

  /* ------------------------------------------------------------------ plots */
  function nice(lo, hi, count) {
    var span = hi - lo;
    if (!(span > 0)) { span = Math.abs(lo) || 1; lo -= span / 2; hi += span / 2; span = hi - lo; }
    var step = Math.pow(10, Math.floor(Math.log10(span / count)));
    [1, 2, 2.5, 5, 10].some(function (m) { if (span / (m * step) <= count) { step *= m; return true; } return false; });
    var ticks = [];
    for (var t = Math.ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) ticks.push(+t.toPrecision(12));
    return ticks;
  }
  function fmt(v) {        // the axes' tick labels; a value is shown as data's text
    if (v === null || v === undefined) return "—";
    var a = Math.abs(v);
    return (a !== 0 && (a >= 1e5 || a < 1e-3)) ? v.toExponential(3) : String(+v.toPrecision(4));
  }

  function charts(data, listeners, setIndex, nearestIndex) {
    var box = document.getElementById("charts");
    var plots = [{ title: data.effort.label + " over the sweep", unit: data.units.effort,
                   series: [{ name: data.effort.label.split(" ").pop(), color: data.effort.color, values: data.effort.values,
                               text: data.effort.text }] },
                 { title: "Joint reactions (magnitude) over the sweep", unit: data.units.force,
                   series: data.joints.map(function (j) { return { name: j.symbol, color: j.color, values: j.f, text: j.text.f }; }) }];
    if (data.shaking) {
      plots.push({ title: "Shaking force on the frame (magnitude) over the sweep", unit: data.units.force,
                   series: [{ name: "|F|", color: data.shaking.color, values: data.shaking.values,
                              text: data.shaking.text }] });
    }
    plots.forEach(function (p) { if (p.series.length) chart(box, data, p, listeners, setIndex, nearestIndex); });
  }

  function chart(box, data, spec, listeners, setIndex, nearestIndex) {
    var W = 640, H = 260, L = 62, R = 12, T = 24, B = 34;
    var xa = data.angles, n = xa.length;
    var fig = el("figure", { "class": "chart" }, box);
    var root = svg("svg", { viewBox: "0 0 " + W + " " + H, role: "img" }, fig);
    text(el("figcaption", {}, fig), spec.title + " [" + spec.unit + "]; " + data.method +
         ". Drag across to zoom, double-click to zoom out.");
    var full = [xa[0], xa[n - 1]];
    if (full[0] > full[1]) full = [full[1], full[0]];
    var view = full.slice();
    var dxs = [];
    for (var i = 1; i < n; i++) dxs.push(Math.abs(xa[i] - xa[i - 1]));
    dxs.sort(function (a, b) { return a - b; });
    var gap = dxs.length ? 1.5 * dxs[Math.floor(dxs.length / 2)] : Infinity;
    var plot = svg("g", {}, root), over = svg("g", {}, root);
    var cursor = svg("line", { y1: T, y2: H - B, stroke: "#222", "stroke-width": 1, "class": "cursor" }, over);
    var dots = spec.series.map(function (s) { return svg("circle", { r: 3.5, fill: s.color }, over); });
    var tip = svg("text", { x: L + 6, y: T - 8, "font-size": 11, "class": "tip" }, over);
    var band = svg("rect", { y: T, height: H - T - B, fill: "rgba(60,120,200,0.15)", visibility: "hidden" }, over);
    var sx, sy, k = 0;

    function draw() {
      while (plot.firstChild) plot.removeChild(plot.firstChild);
      var lo = Infinity, hi = -Infinity;
      spec.series.forEach(function (s) {
        for (var i = 0; i < n; i++) {
          var v = s.values[i];
          if (v !== null && xa[i] >= view[0] && xa[i] <= view[1] && !data.near[i]) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
        }
      });
      if (!isFinite(lo)) { lo = 0; hi = 1; }
      var margin = 0.04 * (hi - lo);          // the curves clear the frame
      lo -= margin; hi += margin;
      var yt = nice(lo, hi, 5), xt = nice(view[0], view[1], 8);
      var y0 = Math.min(yt[0], lo), y1 = Math.max(yt[yt.length - 1], hi);
      sx = function (x) { return L + (x - view[0]) / (view[1] - view[0] || 1) * (W - L - R); };
      sy = function (y) { return H - B - (y - y0) / (y1 - y0 || 1) * (H - T - B); };
      svg("rect", { x: L, y: T, width: W - L - R, height: H - T - B, fill: "#fff", stroke: "#999" }, plot);
      yt.forEach(function (t) {
        svg("line", { x1: L, x2: W - R, y1: sy(t), y2: sy(t), stroke: "#e3e3e3" }, plot);
        text(svg("text", { x: L - 5, y: sy(t) + 4, "text-anchor": "end", "font-size": 10 }, plot), fmt(t));
      });
      xt.forEach(function (t) {
        svg("line", { x1: sx(t), x2: sx(t), y1: T, y2: H - B, stroke: "#eee" }, plot);
        text(svg("text", { x: sx(t), y: H - B + 13, "text-anchor": "middle", "font-size": 10 }, plot), fmt(t));
      });
      text(svg("text", { x: (L + W - R) / 2, y: H - 4, "text-anchor": "middle", "font-size": 11 }, plot),
           data.coord + " [" + (data.unit === "°" ? "deg" : data.unit.trim()) + "]");
      text(svg("text", { x: 12, y: (T + H - B) / 2, "text-anchor": "middle", "font-size": 11,
                         transform: "rotate(-90 12 " + (T + H - B) / 2 + ")" }, plot), "[" + spec.unit + "]");
      data.flagged.forEach(function (a) {
        if (a >= view[0] && a <= view[1]) svg("line", { x1: sx(a), x2: sx(a), y1: T, y2: H - B, stroke: "#d33", "stroke-dasharray": "3 3" }, plot);
      });
      var clip = "clip" + Math.random().toString(36).slice(2);
      var cp = svg("clipPath", { id: clip }, plot);
      svg("rect", { x: L, y: T, width: W - L - R, height: H - T - B }, cp);
      spec.series.forEach(function (s) {
        var parts = [], cur = [];
        for (var i = 0; i < n; i++) {
          var v = s.values[i];
          if (v === null || (i > 0 && Math.abs(xa[i] - xa[i - 1]) > gap)) { if (cur.length) parts.push(cur); cur = []; }
          if (v !== null) cur.push(sx(xa[i]).toFixed(1) + "," + sy(v).toFixed(1));
        }
        if (cur.length) parts.push(cur);
        parts.forEach(function (p) {
          svg("polyline", { points: p.join(" "), fill: "none", stroke: s.color, "stroke-width": 1.6, "clip-path": "url(#" + clip + ")" }, plot);
        });
      });
      place(k);
    }
    function place(i) {
      k = i;
      var x = sx(xa[i]), inside = xa[i] >= view[0] && xa[i] <= view[1];
      cursor.setAttribute("x1", x); cursor.setAttribute("x2", x);
      cursor.setAttribute("visibility", inside ? "visible" : "hidden");
      spec.series.forEach(function (s, j) {
        var v = s.values[i];
        dots[j].setAttribute("visibility", inside && v !== null ? "visible" : "hidden");
        if (v !== null) { dots[j].setAttribute("cx", x); dots[j].setAttribute("cy", sy(v)); }
      });
      label(i);
    }
    function label(i) {
      text(tip, xa[i] + (data.unit === "°" ? "°" : data.unit) + ": " + spec.series.map(function (s) {
        return s.name + " " + s.text[i];      // as the report prints it (units.fmt)
      }).join(", ") + " " + spec.unit);
    }
    function angleAt(ev) {
      var r = root.getBoundingClientRect();
      var px = (ev.clientX - r.left) / r.width * W;
      return view[0] + (px - L) / (W - L - R) * (view[1] - view[0]);
    }
    var start = null;
    root.addEventListener("mousedown", function (ev) { start = angleAt(ev); ev.preventDefault(); });
    root.addEventListener("mousemove", function (ev) {
      var a = angleAt(ev);
      label(nearestIndex(a));
      if (start !== null) {
        var x0 = sx(Math.min(start, a)), x1 = sx(Math.max(start, a));
        band.setAttribute("x", x0); band.setAttribute("width", Math.max(0, x1 - x0));
        band.setAttribute("visibility", "visible");
      }
    });
    root.addEventListener("mouseleave", function () { label(k); });
    root.addEventListener("mouseup", function (ev) {
      var a = angleAt(ev);
      band.setAttribute("visibility", "hidden");
      if (start !== null && Math.abs(sx(a) - sx(start)) > 6) {
        view = [Math.max(full[0], Math.min(start, a)), Math.min(full[1], Math.max(start, a))];
        if (view[1] <= view[0]) view = full.slice();
        draw();
      } else {
        setIndex(nearestIndex(a));
      }
      start = null;
    });
    root.addEventListener("dblclick", function () { view = full.slice(); draw(); });
    listeners.push(place);
    draw();
  }

  /* ------------------------------------------------------------------ index.html */
  function sortable(table) {
    var tbody = table.tBodies[0];
    if (!tbody) return;
    var filter = el("input", { type: "search", placeholder: "Filter the rows…", "aria-label": "filter the rows", "class": "filter" });
    table.parentNode.insertBefore(filter, table);
    filter.addEventListener("input", function () {
      var q = filter.value.toLowerCase();
      Array.prototype.forEach.call(tbody.rows, function (r) {
        r.hidden = q !== "" && r.textContent.toLowerCase().indexOf(q) < 0;
      });
    });
    var heads = table.tHead.rows[0].cells;
    Array.prototype.forEach.call(heads, function (th, col) {
      th.classList.add("sort");
      th.setAttribute("tabindex", "0");
      th.setAttribute("aria-sort", "none");
      function go() {
        var dir = th.getAttribute("aria-sort") === "ascending" ? -1 : 1;
        Array.prototype.forEach.call(heads, function (h) { h.setAttribute("aria-sort", "none"); });
        th.setAttribute("aria-sort", dir === 1 ? "ascending" : "descending");
        var rows = Array.prototype.slice.call(tbody.rows);
        function key(r) {
          var c = r.cells[col], s = c ? c.textContent.trim() : "";
          var m = /^[-+\u2212]?\d[\d.]*(?:[eE][-+]?\d+)?/.exec(s.replace("\u2212", "-"));
          return m ? { n: parseFloat(m[0]), s: s } : { n: null, s: s };
        }
        rows.sort(function (a, b) {
          var ka = key(a), kb = key(b);
          if (ka.n !== null && kb.n !== null && ka.n !== kb.n) return dir * (ka.n - kb.n);
          if ((ka.n === null) !== (kb.n === null)) return ka.n === null ? 1 : -1;
          return dir * ka.s.localeCompare(kb.s);
        });
        rows.forEach(function (r) { tbody.appendChild(r); });
      }
      th.addEventListener("click", go);
      th.addEventListener("keydown", function (ev) { if (ev.key === "Enter" || ev.key === " ") { ev.preventDefault(); go(); } });
    });
  }

  function start() {
    if (document.body.classList.contains("index")) {
      var t = document.querySelector("main table");
      if (t) sortable(t);
      return;
    }
    var block = document.getElementById("mr-data");
    if (block) report(JSON.parse(block.textContent));
  }
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
