#!/usr/bin/env python3
"""Writes a generated class file for scripts/bench-grade.

usage: bench-grade-gen.py repetitive|distinct ROWS OUT.csv

repetitive: students choose among ~10 spellings and mistakes per part across four bank
problems (what a real class looks like). distinct: every answer differs (a varying numeric
coefficient), so nothing can be reused. Seeded: the same file on every run and machine.
"""
import csv
import random
import sys

# Per (problem, part): right answers in several spellings, and the usual mistakes.
CHOICES = {
    ("simple-pendulum", "potential"): [
        "-m*g*l*cos(theta)", "-m g l cos(θ)", "-(m*g*l*cos(theta))", "m*g*l*(-cos(theta))",
        "m*g*l*cos(theta)", "-m*g*l*sin(theta)", "m*g*l*(1-cos(theta))", "-m*g*cos(theta)",
        "m g l cos θ", "-m*l*cos(theta)",
    ],
    ("simple-pendulum", "lagrangian"): [
        "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)", "m l^2 θ'^2/2 + m g l cos(θ)",
        "0.5*m*l^2*theta'^2 + m*g*l*cos(theta)", "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)",
        "1/2*m*l^2*theta'^2", "1/2*m*l*theta'^2 + m*g*l*cos(theta)",
        "m*l^2*theta'^2 + m*g*l*cos(theta)", "1/2*m*l^2*theta'^2 + m*g*l*sin(theta)",
        "1/2*m*(l*theta')^2 + m*g*l*cos(theta)", "1/2*m*l^2*theta'^2 + m*g*cos(theta)",
    ],
    ("simple-pendulum", "eom"): [
        "m*l^2*theta'' + m*g*l*sin(theta) = 0", "m l^2 θ'' + m g l sin(θ) = 0",
        "theta'' + g/l*sin(theta) = 0", "theta'' = -g/l*sin(theta)",
        "m*l^2*theta'' - m*g*l*sin(theta) = 0", "m*l^2*theta'' + m*g*l*theta = 0",
        "m*l^2*theta'' = 0", "m*l*theta'' + m*g*sin(theta) = 0",
        "theta'' + g*sin(theta) = 0", "m*l^2*theta'' + m*g*l*cos(theta) = 0",
    ],
    ("simple-pendulum", "frequencies"): [
        "sqrt(g/l)", "√(g/l)", "(g/l)^(1/2)", "g/l", "sqrt(l/g)", "sqrt(g*l)",
        "2*pi*sqrt(l/g)", "sqrt(g)/sqrt(l)", "sqrt(2*g/l)", "g/l^2",
    ],
    ("simple-pendulum", "equilibria"): [
        "theta = 0; theta = pi", "theta = pi; theta = 0", "θ = 0; θ = π", "theta = 0",
        "theta = pi", "theta = 0; theta = pi/2", "theta = pi/2", "theta = 0; theta = -pi/2",
        "theta=0;theta=pi", "theta = 0; theta = 2*pi",
    ],
    ("spring-incline", "eom"): [
        "m*x'' = -k*x + m*g*sin(alpha)", "m x'' + k x = m g sin(α)",
        "m*x'' + k*x - m*g*sin(alpha) = 0", "m*x'' = k*x - m*g*sin(alpha)",
        "m*x'' = -k*x", "m*x'' = -k*x + m*g*cos(alpha)", "m*x'' = -k*x - m*g*sin(alpha)",
        "x'' = -k/m*x + g*sin(alpha)", "m*x'' = -k*x + m*g", "m*x'' = m*g*sin(alpha)",
    ],
    ("spring-incline", "equilibria"): [
        "x = m*g*sin(alpha)/k", "x = m g sin(α)/k", "x = m*g/k", "x = 0",
        "x = m*g*cos(alpha)/k", "x = -m*g*sin(alpha)/k", "x = k/(m*g*sin(alpha))",
        "x = g*sin(alpha)/k", "x=m*g*sin(alpha)/k", "x = 2*m*g*sin(alpha)/k",
    ],
    ("atwood", "eom"): [
        "(m1+m2)*x'' = (m1-m2)*g", "(m1 + m2) x'' = (m1 - m2) g",
        "x'' = (m1-m2)/(m1+m2)*g", "(m1+m2)*x'' = -(m1-m2)*g", "(m1+m2)*x'' = (m1+m2)*g",
        "(m1-m2)*x'' = (m1+m2)*g", "x'' = g", "m1*x'' = (m1-m2)*g",
        "(m1+m2)*x'' - (m1-m2)*g = 0", "(m1+m2)*x'' = m1*g",
    ],
    ("bead-wire", "eom"): [
        "r'' = omega^2*r", "r'' = ω² r", "r'' - omega^2*r = 0", "m*r'' = m*omega^2*r",
        "r'' = -omega^2*r", "r'' = 0", "r'' = 2*omega^2*r", "r'' = omega*r",
        "r'' + omega^2*r = 0", "m*r'' = omega^2*r",
    ],
}

# Per part: an answer with a numeric coefficient (distinct for every row).
TEMPLATES = [
    ("simple-pendulum", "potential", "-{c}*m*g*l*cos(theta)"),
    ("simple-pendulum", "eom", "m*l^2*theta'' + {c}*m*g*l*sin(theta) = 0"),
    ("simple-pendulum", "frequencies", "sqrt({c}*g/l)"),
    ("spring-incline", "eom", "m*x'' = -{c}*k*x + m*g*sin(alpha)"),
    ("atwood", "eom", "(m1+m2)*x'' = {c}*(m1-m2)*g"),
]


def main():
    kind, rows, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    rng = random.Random(11)
    parts = sorted(CHOICES)
    with open(out, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["student", "problem", "part", "answer"])
        for i in range(rows):
            student = f"s{i // len(parts):06d}"
            if kind == "repetitive":
                problem, part = parts[i % len(parts)]
                # The first choices are the most common, as in a class.
                choices = CHOICES[(problem, part)]
                k = min(int(rng.expovariate(0.45)), len(choices) - 1)
                answer = choices[k]
            else:
                problem, part, template = TEMPLATES[i % len(TEMPLATES)]
                answer = template.format(c=f"{1 + (i + 1) / 1_000_000:.6f}")
            w.writerow([student, problem, part, answer])


if __name__ == "__main__":
    main()
