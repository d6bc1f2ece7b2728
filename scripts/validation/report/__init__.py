"""The validation report of scripts/validation/make_validation_md.py, in parts:

  runs.py           the data: the paper's numbers, the groups of runs of each study, Run
  text.py           formatting of numbers, cells and tables
  measures.py       what is measured on a run beyond summary.json (fits, budgets, VTK reads)
  figures.py        the figures (comparison plots, plot_collapse.py's figures copied in)
  case_a.py         the sections of case A, with their criteria
  case_b.py         the sections of case B, with their criteria
  studies.py        the studies of the numerical choices the paper leaves open
  disagreements.py  "Known disagreements"
  document.py       the head, the criteria table, the order of the sections
"""
