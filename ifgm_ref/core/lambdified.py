"""The Python code :func:`sympy.lambdify` prints for each formula the package declares.

Written by ``python -m ifgm_ref.apps.formula_table``; ``tests/test_formulas.py`` checks it
against the installed sympy. :func:`ifgm_ref.core.formulas.evaluate` runs this code, so a
process that evaluates a declared formula does not import sympy.
"""

#: Formula -> the expression lambdify prints for it, over ``r, v, w, dt, R, res, fov``.
LAMBDIFIED: dict[str, str] = {
    "0.02": "0.0200000000000000",
    "0.1": "0.100000000000000",
    "0.4*r/4.4": "0.0909090909090909*r",
    "0.75": "0.750000000000000",
    "1": "1",
    "12*r": "12*r",
    "2*pi*r": "2*pi*r",
    "2*pi/w": "2*pi/w",
    "2*r": "2*r",
    "2*r/4.4": "0.454545454545455*r",
    "20": "20",
    "200*r/4.4": "45.4545454545455*r",
    "3*r": "3*r",
    "5*r": "5*r",
    "50*r**4": "50*r**4",
    "50*r/4.4": "11.3636363636364*r",
    "6": "6",
    "6*r/4.4": "1.36363636363636*r",
    "6.5*r/4.4": "1.47727272727273*r",
    "60*r/4.4": "13.6363636363636*r",
    "8": "8",
    "8*r": "8*r",
    "9*r": "9*r",
    "Max(2*r/3, pi*r/(2*fov))": "max((2/3)*r, (1/2)*pi*r/fov)",
    "Max(6*pi/w, 10*r/v, 20*dt)": "max(20*dt, 6*pi/w, 10*r/v)",
    "Min(R, 15*r)": "min(R, 15*r)",
    "dt": "dt",
    "r": "r",
    "r + v/2": "r + (1/2)*v",
    "r/2": "(1/2)*r",
    "r/4": "(1/4)*r",
    "r/4.4": "0.227272727272727*r",
    "v*dt": "dt*v",
    "v/(2*dt)": "(1/2)*v/dt",
    "v/10": "(1/10)*v",
    "v/2": "(1/2)*v",
    "w*dt/2": "(1/2)*dt*w",
    "w/(pi*dt)": "w/(pi*dt)",
    "w/10": "(1/10)*w",
    "w/2": "(1/2)*w",
}
