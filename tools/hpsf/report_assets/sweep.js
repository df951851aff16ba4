// The charts of hpsf sweep's page (sweep.tpl), drawn with uPlot from the sweep's JSON. uPlot's aligned mode wants
// one x array for all series, so the x values of every series are merged and each series holds null where it has no
// point; a frontier line spans those gaps, a scatter series draws no line at all. When done, <body> gets
// data-ready="1" and data-charts (how many charts were drawn); an error is recorded in data-errors, so a headless
// browser can tell.
(function () {
  "use strict";
  var errors = [];
  window.addEventListener("error", function (e) {
    errors.push(String(e.message));
    document.body.setAttribute("data-errors", errors.join(" | "));
  });
  var palette = ["#f78c29", "#59b3f2", "#73d966", "#e666bf", "#f2d94d", "#9980f2", "#4dd9c7", "#f26d6d",
                 "#b3b34d", "#c78cf2"];
  function colourOf(method, index) {
    return method === "pt" || method.indexOf("pt,") === 0 ? "#d9d9d9" : palette[index % palette.length];
  }
  // What a frontier runs over: a method (a hashed one per backend) after a number of frames.
  function frontierKey(c) {
    return c.method + (c.backend === "-" ? "" : "/" + c.backend) +
           (c.frames > 1 ? ", " + c.frames + " frames" : "");
  }

  // Merges the series' x values (sorted, unique) and spreads each series' y over them.
  function aligned(seriesPoints) {
    var xs = [];
    seriesPoints.forEach(function (points) { points.forEach(function (p) { xs.push(p[0]); }); });
    xs.sort(function (a, b) { return a - b; });
    xs = xs.filter(function (x, i) { return i === 0 || x !== xs[i - 1]; });
    var data = [xs];
    seriesPoints.forEach(function (points) {
      var ys = xs.map(function () { return null; });
      points.forEach(function (p) { ys[xs.indexOf(p[0])] = p[1]; });
      data.push(ys);
    });
    return data;
  }

  // Tick labels that stay readable over many decades: 1e-4 rather than uPlot's 0.
  function ticks(u, values) {
    return values.map(function (v) { return v === null ? "" : v >= 0.01 && v < 1e4 ? String(v) : v.toExponential(0); });
  }

  // xLog: the x axis's logarithm base (2 for filter widths, which a sweep doubles; 10 for times).
  // yDistr: uPlot's distribution of the y scale, 3 (log, the default) or 1 (linear, for counts that may be 0).
  function chart(id, xLabel, yLabel, xLog, series, points, yDistr) {
    var target = document.getElementById(id);
    var width = Math.min(1100, target.clientWidth || 1100);
    var options = {
      width: width, height: 460,
      scales: { x: { time: false, distr: 3, log: xLog }, y: { distr: yDistr || 3 } },
      axes: [{ label: xLabel, stroke: "#c9ccd1", grid: { stroke: "#3a3d42" }, values: ticks },
             { label: yLabel, stroke: "#c9ccd1", grid: { stroke: "#3a3d42" }, values: ticks, size: 60 }],
      series: [{ label: xLabel }].concat(series),
      legend: { live: false }
    };
    return new uPlot(options, aligned(points), target);
  }

  function noLine() { return null; }
  function positive(v) { return typeof v === "number" && v > 0 && isFinite(v); }

  var configs = JSON.parse(document.getElementById("sweep-data").textContent);
  var drawn = 0;
  var methods = [];
  configs.forEach(function (c) {
    var key = frontierKey(c);
    if (methods.indexOf(key) < 0) methods.push(key);
  });
  var series = [], points = [];
  methods.forEach(function (key, m) {
    var mine = configs.filter(function (c) {
      return frontierKey(c) === key && positive(c.total_s) && positive(c.relmse);
    });
    var colour = colourOf(key, m);
    series.push({ label: key, stroke: colour, paths: noLine, points: { show: true, size: 7, fill: colour } });
    points.push(mine.map(function (c) { return [c.total_s, c.relmse]; }));
    series.push({ label: key + " frontier", stroke: colour, width: 1.5, spanGaps: true, points: { show: false } });
    points.push(mine.filter(function (c) { return c.frontier; }).map(function (c) { return [c.total_s, c.relmse]; }));
  });
  chart("pareto", "seconds per frame", "relMSE", 10, series, points);
  ++drawn;

  // Fireflies (pixels past 5 sigma of path tracing at their spp) against time, one series per configuration's
  // method and filter settings other than the spp, so plain, multi-level and other filters read apart.
  var fireflyGroups = {}, fireflyOrder = [];
  configs.forEach(function (c) {
    if (typeof c.fireflies !== "number" || !positive(c.total_s)) return;
    var label = c.method + (c.backend === "-" ? "" : "/" + c.backend) + (c.filter ? " " + Object.keys(c.filter).sort()
      .map(function (k) { return k + "=" + c.filter[k]; }).join(" ") : "");
    if (!fireflyGroups[label]) { fireflyGroups[label] = []; fireflyOrder.push(label); }
    fireflyGroups[label].push([c.total_s, c.fireflies]);
  });
  var fireflySeries = [], fireflyPoints = [];
  fireflyOrder.forEach(function (label, g) {
    var colour = colourOf(label.split("/")[0].split(" ")[0], g);
    fireflySeries.push({ label: label, stroke: colour, width: 1.5, spanGaps: true,
                         points: { show: true, size: 7, fill: colour } });
    fireflyPoints.push(fireflyGroups[label].sort(function (a, b) { return a[0] - b[0]; }));
  });
  chart("fireflies", "seconds per frame", "fireflies per image", 10, fireflySeries, fireflyPoints, 1);
  ++drawn;

  // Groups of configurations that differ only in their filter width.
  var groups = {}, order = [];
  configs.forEach(function (c) {
    if (!c.filter || c.filter["filter-width"] === undefined) return;
    var width = Number(c.filter["filter-width"]);
    var label = c.id.replace(" filter-width=" + c.filter["filter-width"], "").replace(" backend=-", "");
    if (!groups[label]) { groups[label] = []; order.push(label); }
    groups[label].push(c);
    c.width = width;
  });
  order = order.filter(function (label) { return groups[label].length >= 2; });
  // The legend names what tells the groups apart: the words every group shares are left out.
  var shared = order.length > 1 ? order[0].split(" ").filter(function (word) {
    return order.every(function (label) { return label.split(" ").indexOf(word) >= 0; });
  }) : [];
  function short(label) {
    var words = label.split(" ").filter(function (word) { return shared.indexOf(word) < 0; });
    return words.length > 0 ? words.join(" ") : label;
  }
  if (order.length > 0) {
    var widthSeries = [], widthPoints = [];
    order.forEach(function (label, g) {
      var colour = palette[g % palette.length];
      var group = groups[label];
      widthSeries.push({ label: short(label) + " bias^2", stroke: colour, width: 2,
                         points: { show: true, fill: colour } });
      widthPoints.push(group.filter(function (c) { return positive(c.rel_bias2); })
                            .map(function (c) { return [c.width, c.rel_bias2]; }));
      widthSeries.push({ label: short(label) + " variance", stroke: colour, dash: [6, 4], points: { show: true } });
      widthPoints.push(group.filter(function (c) { return positive(c.rel_variance); })
                            .map(function (c) { return [c.width, c.rel_variance]; }));
    });
    chart("width", "filter width (px)", "relMSE term", 2, widthSeries, widthPoints);
    ++drawn;
  } else {
    document.getElementById("no-width").hidden = false;
  }
  // relMSE after each frame: one line per group of configurations that differ only in their frames, the longest
  // (a shorter one's frames are its first).
  var longest = {}, sequences = [];
  configs.forEach(function (c) {
    if (!Array.isArray(c.relmse_by_frame)) return;
    var group = c.id.replace(" frames=" + c.frames, "");
    if (longest[group] === undefined) { longest[group] = sequences.length; sequences.push(c); }
    else if (c.frames > sequences[longest[group]].frames) sequences[longest[group]] = c;
  });
  if (sequences.length > 0) {
    var frameSeries = [], framePoints = [];
    var sharedWords = sequences[0].id.split(" ").filter(function (word) {
      return sequences.every(function (c) { return c.id.split(" ").indexOf(word) >= 0; });
    });
    sequences.forEach(function (c, g) {
      var colour = colourOf(c.method, g);
      var label = c.id.split(" ").filter(function (word) {
        return sharedWords.indexOf(word) < 0 && word !== "backend=-" && word.indexOf("frames=") !== 0;
      }).join(" ") || c.method;
      frameSeries.push({ label: label, stroke: colour, width: 1.5, spanGaps: true, points: { show: false } });
      framePoints.push(c.relmse_by_frame.map(function (e, f) { return [f + 1, positive(e) ? e : null]; }));
    });
    chart("frames", "frames", "relMSE", 2, frameSeries, framePoints);
    ++drawn;
  } else {
    document.getElementById("no-frames").hidden = false;
  }
  document.body.setAttribute("data-charts", String(drawn));
  document.body.setAttribute("data-ready", "1");
})();
