{{%AUTOESCAPE context="HTML"}}{{!
  The page hpsf sweep writes beside its CSV (OUT/sweep.html): the Pareto plot of relMSE against time per frame and
  the plot of relMSE's bias^2 and variance against filter width, drawn by uPlot (npm "uplot", MIT, embedded: the page
  needs no network), and a table of every configuration, readable without the script. The data the charts draw is
  the sweep's own JSON, in a script element of type application/json. :none marks what the C++ embeds unchanged
  (the style, the library, the script, the data with every "</" escaped).
}}<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="hpsf {{VERSION}}">
<title>{{TITLE}}</title>
<style>{{STYLE:none}}</style>
<style>{{UPLOT_CSS:none}}</style>
</head>
<body class="sweep">
<header class="page">
<h1>{{TITLE}}</h1>
<p class="counts">{{CONFIGURATIONS}} configurations, against {{REFERENCE}}</p>
</header>
<section class="chart">
<h2>relMSE against time per frame (trace + filter), log-log</h2>
<p>Every configuration is a point; each method's frontier (no configuration of it both faster and more accurate) a
line. Plain path tracing's frontier is the line to beat at equal time.</p>
<div id="pareto"></div>
</section>
<section class="chart">
<h2>Fireflies against time per frame</h2>
<p>The pixels of an image further from the converged image than 5 standard deviations of path tracing at their spp,
in some channel (mean over the seeds; verifier/metrics/fireflies.h). One line per method and filter settings, over
the spp swept.</p>
<div id="fireflies"></div>
</section>
<section class="chart">
<h2>relMSE's bias^2 and variance against filter width</h2>
<p>One colour per configuration swept only in its filter width: bias^2 solid, variance dashed. A bias^2 at or below
0 (below what the seeds resolve) is left out.</p>
<div id="width"></div>
<p id="no-width" hidden>The grid sweeps fewer than two filter widths.</p>
</section>
<section class="chart">
<h2>relMSE against frames</h2>
<p>One line per configuration of more than one frame: its relMSE after each frame (mean over the seeds). The
methods of several filtered bounces gain a bounce a frame; path tracing and plain HPSF only average.</p>
<div id="frames"></div>
<p id="no-frames" hidden>The grid runs no configuration of more than one frame.</p>
</section>
<table class="configurations">
<thead><tr><th>configuration</th><th>method</th><th>spp</th><th>frames</th><th>s per frame</th><th>relMSE</th><th>SSIM</th><th>fireflies</th>
<th>bias^2</th><th>variance</th><th>on its frontier</th><th>pt's relMSE at equal time</th></tr></thead>
<tbody>
{{#CONFIG}}<tr><td>{{ID}}</td><td>{{METHOD}}</td><td>{{SPP}}</td><td>{{FRAMES}}</td><td>{{TOTAL_S}}</td><td>{{RELMSE}}</td>
<td>{{SSIM}}</td><td>{{FIREFLIES}}</td><td>{{REL_BIAS2}}</td><td>{{REL_VARIANCE}}</td><td>{{FRONTIER}}</td><td>{{PT_AT_EQUAL_TIME}}</td></tr>
{{/CONFIG}}
</tbody>
</table>
<script type="application/json" id="sweep-data">{{DATA:none}}</script>
<script>{{UPLOT_JS:none}}</script>
<script>{{SCRIPT:none}}</script>
</body>
</html>
