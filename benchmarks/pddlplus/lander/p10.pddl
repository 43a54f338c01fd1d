(define (problem lander-10)
  (:domain lander)
  (:init
    (flying)
    (= (h) 5036.6) (= (v) -80)
    (= (mass) 1183.81) (= (fuel) 183.81) (= (burn-rate) 5)
    (= (gravity) 3.71) (= (thrust) 8783.9)
    (= (touch-height) 0.5) (= (safe-speed) 1))
  (:goal (and (landed))))
