{{%AUTOESCAPE context="HTML"}}{{!
  The page of `hpsf check --html`: one row per gate case, in gate order, with its outcome, time, first failure or
  warning, and (unfolded) every failure, the command that reproduces it, its repro bundle and its own report; above
  them the split by family. ctemplate escapes every variable for the place it stands in; :none marks the style,
  which the C++ embeds unchanged. The filter needs no script to read the page: it only hides rows.
}}<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="hpsf {{VERSION}}">
<title>{{TITLE}}</title>
<style>{{STYLE:none}}</style>
</head>
<body class="check">
<header class="page">
<h1>{{TITLE}}</h1>
<p class="counts">{{CASE_COUNT}} cases of {{GATE_CASES}} in the gate (shard {{SHARD}}), {{SECONDS}} s:
{{#OUTCOME_COUNT}}<span class="verdict {{OUTCOME_CLASS}}">{{N}} {{OUTCOME}}</span> {{/OUTCOME_COUNT}}</p>
</header>
<table class="summary families">
<caption>by family</caption>
<thead><tr><th>family</th><th>cases</th><th>pass</th><th>warn</th><th>fail</th><th>error</th><th>seconds</th></tr></thead>
<tbody>
{{#FAMILY}}<tr><td>{{FAMILY}}</td><td>{{CASES}}</td><td>{{PASSED}}</td><td>{{WARNED}}</td><td>{{FAILED}}</td><td>{{ERRORS}}</td>
<td>{{SECONDS}}</td></tr>
{{/FAMILY}}
</tbody>
</table>
<p class="filter"><label><input type="checkbox" id="only-problems"> only the cases that did not pass</label></p>
<table class="cases">
<thead><tr><th>#</th><th>outcome</th><th>case</th><th>seconds</th><th>first failure or warning</th></tr></thead>
<tbody>
{{#CASE}}<tr class="case {{OUTCOME_CLASS}}" id="{{ANCHOR}}">
<td>{{INDEX}}</td><td><span class="verdict {{OUTCOME_CLASS}}">{{OUTCOME}}</span></td>
<td><a href="#{{ANCHOR}}">{{ID}}</a></td><td>{{SECONDS}}</td>
<td>{{#PROBLEM}}<details><summary>{{MESSAGE}}</summary>
<pre class="details">{{DETAILS}}</pre>
</details>{{/PROBLEM}}
<p class="reproduce">reproduce: <code>{{REPRODUCE}}</code></p>
{{#BUNDLE}}<p class="bundle">repro bundle: <code>{{BUNDLE}}</code></p>{{/BUNDLE}}
{{#FIXED_POINT}}<p class="fixed-point">accumulation: {{FIXED_POINT}}</p>{{/FIXED_POINT}}
{{#CASE_REPORT}}<p class="case-report"><a href="{{HREF}}">the case's report</a></p>{{/CASE_REPORT}}
</td></tr>
{{/CASE}}
</tbody>
</table>
<script>
document.getElementById("only-problems").addEventListener("change", function (event) {
  for (const row of document.querySelectorAll("tr.case.pass")) row.hidden = event.target.checked;
});
</script>
</body>
</html>
