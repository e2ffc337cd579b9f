#!/usr/bin/python3
"""Evaluates the worked cubic with the freeform package and prints it as
``freeform eval --format csv`` prints examples/cubic_bezier.json.

The cubic Bezier curve (0,0), (1,2), (3,2), (4,0) at t = 0, 0.5, 1 with its
first derivative: the points (0,0), (2,1.5), (4,0) and the derivatives
(3,6), (4.5,0), (3,-6).

    python3 clients/python/examples/worked_cubic.py --address 127.0.0.1:50051

prints the same text as

    freeform eval --address 127.0.0.1:50051 \\
        --file examples/cubic_bezier.json --format csv

(numbers as C++'s std::to_chars writes them, see to_chars below).
"""

import argparse
import decimal
import math
import sys

import freeform


def to_chars(value: float) -> str:
    """The text std::to_chars(value) gives: the shortest digits that read
    back as the same double, in fixed or scientific notation, whichever is
    shorter (fixed on a tie)."""
    if math.isnan(value):
        return "nan"
    if math.isinf(value):
        return "inf" if value > 0 else "-inf"
    sign = "-" if math.copysign(1, value) < 0 else ""
    # repr gives the shortest round-trip digits; normalize drops the
    # trailing zeros ("4.0" -> 4).
    _, digit_tuple, exponent = decimal.Decimal(
        repr(abs(value))).normalize().as_tuple()
    digits = "".join(map(str, digit_tuple))
    if exponent >= 0:
        # An integer: std::to_chars writes all its exact digits.
        fixed = str(int(abs(value)))
    elif -exponent < len(digits):
        fixed = digits[:exponent] + "." + digits[exponent:]
    else:
        fixed = "0." + "0" * (-exponent - len(digits)) + digits
    power = exponent + len(digits) - 1
    scientific = "%s%se%s%02d" % (
        digits[0], "." + digits[1:] if len(digits) > 1 else "",
        "-" if power < 0 else "+", abs(power))
    return sign + (fixed if len(fixed) <= len(scientific) else scientific)


def print_csv(samples: freeform.CurveSamples) -> None:
    """The CLI's CSV: index, the point, then each derivative."""
    orders, count, dimension = samples.derivatives.shape
    header = ["index"] + ["%sx%d" % ("d%d" % k if k else "", j)
                          for k in range(orders) for j in range(dimension)]
    print(",".join(header))
    for index in range(count):
        row = samples.derivatives[:, index, :].reshape(-1)
        print(",".join([str(samples.first_index + index)] +
                       [to_chars(float(value)) for value in row]))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--address", default="127.0.0.1:50051",
                        help="freeformd's HOST:PORT")
    args = parser.parse_args()
    cubic = freeform.bezier([[0, 0], [1, 2], [3, 2], [4, 0]])
    try:
        with freeform.Client(args.address, timeout=10) as client:
            print_csv(client.curves.evaluate(cubic, [0, 0.5, 1],
                                             derivative_order=1))
    except freeform.FreeformError as error:
        print("error: %s" % error, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
